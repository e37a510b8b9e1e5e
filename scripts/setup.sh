#!/usr/bin/env bash
# Installs every Debian package a3rig needs, then configures and builds it with CMake
# (Release, warnings as errors). Idempotent: run it again after a pull.
# Usage: scripts/setup.sh [--no-install] [--build-dir DIR] [--debug]
#   --no-install   skip apt-get (the packages are already there, or you are not root)
#   --build-dir    build folder (default: build/ in the repository)
#   --debug        Debug build instead of Release
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build_dir="$repo/build"
build_type=Release
install=1
while [ $# -gt 0 ]; do
  case "$1" in
    --no-install) install=0 ;;
    --build-dir) build_dir=$2; shift ;;
    --debug) build_type=Debug ;;
    -h|--help) sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "setup.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done

# One line per library, with what it is for (the README's "Libraries" table says the same).
packages=(
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
  libgoogle-perftools-dev                        # tcmalloc: the scorer allocates a lot in valijson
  libgtest-dev libgmock-dev libbenchmark-dev     # tests and benchmarks
  clang libclang-rt-dev                          # libFuzzer + sanitizer runtimes for scripts/fuzz.sh (fuzz/)
  json-schema-test-suite                         # the official JSON Schema test cases
  gnuplot-nox                                    # leaderboard plots (PNG)
  python3 python3-jsonschema                     # the Python reference scorer (cross-check, baseline)
  python3-scipy python3-numpy                    # SciPy baseline of the dynamics benchmark (bench/dynamics)
  iproute2                                       # multicast loopback route for LCM's UDP transport
  nodejs                                         # official OpenAI / MCP SDK clients in tests/npm (npm: below)
  libjs-d3                                       # d3, inlined into each episode report (a3rig report)
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
  if [ ! -e /usr/bin/npm ]; then
    apt-get install -y -qq --no-install-recommends npm >/dev/null
  fi
fi

generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
if [ -f "$build_dir/CMakeCache.txt" ]; then generator=(); fi
echo "setup.sh: configuring $build_dir ($build_type)"
cmake -S "$repo" -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE="$build_type" -DA3_WERROR=ON >/dev/null
echo "setup.sh: building"
cmake --build "$build_dir" -j "$(nproc)"
echo "setup.sh: done; the program is $build_dir/a3rig"
