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
started_s=$SECONDS
"$repo/scripts/setup.sh" "${install[@]}" --build-dir "$build_dir"
built_s=$SECONDS

if [ "$(id -u)" = 0 ]; then
  if "$repo/scripts/lcm-loopback.sh"; then
    export A3_REQUIRE_UDPM=1
  fi
fi
export A3_SHARED_DIR=${A3_SHARED_DIR:-$repo/../shared}
[ -d "$A3_SHARED_DIR/alphabench" ] || echo "test.sh: $A3_SHARED_DIR/alphabench not found: tests that need the α³-Bench public episodes will be skipped (put ../shared beside the repository or set A3_SHARED_DIR)"

echo "test.sh: running the tests"
ctest_status=0
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" "$@" || ctest_status=$?
tested_s=$SECONDS

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
# The closing time table (the per-label times are ctest's "Label Time Summary" above): the
# suite's budget is 40 minutes on 2 cores, build included, so drift shows here first.
awk -v build=$((built_s - started_s)) -v tests=$((tested_s - built_s)) -v fuzz=$((SECONDS - tested_s)) 'BEGIN {
  printf "test.sh: times: set-up and build %d s, tests %d s, fuzz %d s; total %.1f min (budget 40)\n",
         build, tests, fuzz, (build + tests + fuzz) / 60 }'
exit "$ctest_status"
