#!/usr/bin/env bash
# The test command: installs the Debian packages, builds (Release, warnings as errors) and runs
# every test, then each fuzz target briefly (scripts/fuzz.sh). As root it also routes LCM's
# multicast group over loopback, so the LCM UDP tests run for real (A3_REQUIRE_UDPM=1 makes them
# fail, not skip, if that does not work).
# Usage: scripts/test.sh [ctest arguments...]   e.g. scripts/test.sh -L eval
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${A3_BUILD_DIR:-$repo/build}
install=()
[ "$(id -u)" = 0 ] || install=(--no-install)
"$repo/scripts/setup.sh" "${install[@]}" --build-dir "$build_dir"

if [ "$(id -u)" = 0 ]; then
  if "$repo/scripts/lcm-loopback.sh"; then
    export A3_REQUIRE_UDPM=1
  fi
fi
export A3_SHARED_DIR=${A3_SHARED_DIR:-$repo/../shared}
[ -d "$A3_SHARED_DIR/alphabench" ] || echo "test.sh: $A3_SHARED_DIR/alphabench not found: tests that need the α³-Bench public episodes will be skipped (put ../shared beside the repository or set A3_SHARED_DIR)"

echo "test.sh: running the tests"
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" "$@"

# The fuzz targets for a fixed number of executions each, in their own build (clang, sanitizers;
# scripts/fuzz.sh SECONDS runs them longer). A3_FUZZ_RUNS=0 skips them.
fuzz_runs=${A3_FUZZ_RUNS:-1000}
if [ "$fuzz_runs" = 0 ]; then
  echo "test.sh: fuzz targets skipped (A3_FUZZ_RUNS=0)"
else
  echo "test.sh: running each fuzz target for $fuzz_runs executions"
  "$repo/scripts/fuzz.sh" --runs "$fuzz_runs" --build-dir "$build_dir-fuzz"
fi
