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
# scripts/fuzz.sh SECONDS runs them longer). Only the targets that do not need a3_agent by default:
# their libraries build in about 3 minutes on 2 cores, all seven targets' in about 8 (a3_agent
# alone is 5 CPU-minutes); tests/fuzz_replay replays every target's seeds and findings in the
# main build. A3_FUZZ_TARGETS="all" (or a list) widens it; A3_FUZZ_RUNS=0 skips fuzzing.
fuzz_runs=${A3_FUZZ_RUNS:-2000}
fuzz_targets=${A3_FUZZ_TARGETS:-dronecan fc_command episode}
if [ "$fuzz_runs" = 0 ]; then
  echo "test.sh: fuzz targets skipped (A3_FUZZ_RUNS=0)"
else
  target_args=()
  if [ "$fuzz_targets" != all ]; then
    for name in $fuzz_targets; do target_args+=(--target "$name"); done
  fi
  echo "test.sh: running fuzz targets ($fuzz_targets) for $fuzz_runs executions each"
  "$repo/scripts/fuzz.sh" --runs "$fuzz_runs" --build-dir "$build_dir-fuzz" "${target_args[@]}"
fi
