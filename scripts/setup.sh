#!/usr/bin/env bash
# Installs the Debian packages a3rig needs, then configures and builds it with CMake
# (Release, warnings as errors). Idempotent: run it again after a pull.
# Usage: scripts/setup.sh [--program-only] [--no-install] [--build-dir DIR] [--debug]
#   --program-only only what building and running the a3rig program needs, and only that
#                  program (the main job's first flight); default: everything the tests,
#                  benchmarks and tools need too, and every target
#   --no-install   skip apt-get (the packages are already there, or you are not root)
#   --build-dir    build folder (default: build/ in the repository)
#   --debug        Debug build instead of Release
# ccache is used when it is installed (apt-get install ccache); nothing requires it.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build_dir="$repo/build"
build_type=Release
install=1
program_only=0
while [ $# -gt 0 ]; do
  case "$1" in
    --program-only) program_only=1 ;;
    --no-install) install=0 ;;
    --build-dir) build_dir=$2; shift ;;
    --debug) build_type=Debug ;;
    -h|--help) sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "setup.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done

# One line per library, with what it is for (the README's "Libraries" table says the same).
# What building and running the a3rig program needs:
program_packages=(
  build-essential cmake ninja-build pkg-config   # compiler and build
  liblcm-dev liblcm-bin libglib2.0-dev           # LCM publish/subscribe, lcm-gen (lcm.pc needs glib)
  libeigen3-dev                                  # linear algebra for the vehicle model
  libode-dev                                     # Open Dynamics Engine integrator
  libsundials-dev                                # SUNDIALS CVODE integrator
  nlohmann-json3-dev                             # JSON for configuration and episode writing
  rapidjson-dev                                  # JSON parsing: the reference parser of scoring
  libsimdjson-dev                                # SIMD JSON parsing: scoring's fast path
  libvalijson-dev                                # JSON Schema validation
  libcli11-dev                                   # command line
  libcurl4-openssl-dev                           # HTTP client for LLM endpoints
  libcpp-httplib-dev                             # HTTP server for the offline model server
  libssl-dev                                     # OpenSSL: SHA-256 of the reports' scripts (CSP), constant-time key compare
  libgoogle-perftools-dev                        # tcmalloc: the scorer allocates a lot in valijson
  gnuplot-nox                                    # trajectory and leaderboard plots (PNG)
  libjs-d3                                       # d3, inlined into each episode report (a3rig report)
  iproute2                                       # multicast loopback route for LCM's UDP transport
)
# What the tests, benchmarks, fuzzing and tools need besides:
test_packages=(
  libgtest-dev libgmock-dev libbenchmark-dev     # tests and benchmarks
  clang libclang-rt-dev                          # libFuzzer + sanitizer runtimes for scripts/fuzz.sh (fuzz/)
  json-schema-test-suite                         # the official JSON Schema test cases
  python3 python3-jsonschema                     # the Python reference scorer (cross-check, baseline)
  python3-scipy python3-numpy                    # SciPy baseline of the dynamics benchmark (bench/dynamics)
  nodejs                                         # official OpenAI / MCP SDK clients in tests/npm (npm: below)
  chromium python3-pil fonts-dejavu-core         # tests/report: reports rendered headless, screenshots checked
  default-jdk-headless default-jre liblcm-java   # Java LCM types jar (javac, lcm.jar) for scripts/lcm-spy.sh (a GUI: a full JRE)
  libjchart2d-java                               # lcm-spy's charts (liblcm-java does not depend on it)
  xvfb xauth                                     # lcm-spy and lcm-logplayer-gui headless in tests/tools (xvfb-run)
  strace dpkg-dev                                # tests/package: the installed a3rig's file accesses; cpack's dpkg-shlibdeps
  # Real SocketCAN for the CAN tests on kernels without it (scripts/vcan-vm): QEMU boots
  # Debian's kernel (fetched with apt-get download, not installed) from a busybox
  # initramfs; can-utils gives candump/cansend; python3 unpacks the kernel image.
  qemu-system-x86 busybox-static can-utils
)

packages=("${program_packages[@]}")
[ "$program_only" = 1 ] || packages+=("${test_packages[@]}")

if [ "$install" = 1 ]; then
  if [ "$(id -u)" != 0 ]; then
    echo "setup.sh: installing packages needs root (or pass --no-install if they are installed)" >&2
    exit 1
  fi
  echo "setup.sh: installing Debian packages (apt-get update first)"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
  # Some nodejs packages ship npm themselves, and Debian's npm conflicts with them.
  if [ "$program_only" = 0 ] && [ ! -e /usr/bin/npm ]; then
    apt-get install -y -qq --no-install-recommends npm >/dev/null
  fi
fi

generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
options=(-DCMAKE_BUILD_TYPE="$build_type" -DA3_WERROR=ON)
command -v ccache >/dev/null 2>&1 && options+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
targets=()
if [ -f "$build_dir/CMakeCache.txt" ]; then
  generator=()
  # A folder configured for the tests keeps them (its packages are there); only the target narrows.
  [ "$program_only" = 1 ] || options+=(-DA3_BUILD_TESTS=ON -DA3_BUILD_BENCH=ON)
elif [ "$program_only" = 1 ]; then
  options+=(-DA3_BUILD_TESTS=OFF -DA3_BUILD_BENCH=OFF)
else
  options+=(-DA3_BUILD_TESTS=ON -DA3_BUILD_BENCH=ON)
fi
[ "$program_only" = 1 ] && targets=(--target a3rig)
echo "setup.sh: configuring $build_dir ($build_type)"
cmake -S "$repo" -B "$build_dir" "${generator[@]}" "${options[@]}" >/dev/null
echo "setup.sh: building${targets[*]:+ ${targets[*]}}"
cmake --build "$build_dir" -j "$(nproc)" "${targets[@]}"
echo "setup.sh: done; the program is $build_dir/a3rig"
