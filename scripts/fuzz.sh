#!/usr/bin/env bash
# The libFuzzer targets (fuzz/): configures and builds them in their own folder (clang, -O1 -g,
# AddressSanitizer + UndefinedBehaviorSanitizer, only the fuzz targets and the libraries they
# link), runs each on its seed corpus, and prints per target the executions, executions per
# second, coverage, new corpus inputs and findings (crash, leak, timeout, out-of-memory files).
# Exit status 1 on any finding.
# Usage: scripts/fuzz.sh [SECONDS] [--runs N] [--target NAME]... [--build-dir DIR] [--no-build]
#   SECONDS       run each target this long (default 60)
#   --runs N      run each target for N executions instead (CI: a fixed amount of work)
#   --target NAME only this target (repeatable); default: every target in fuzz/targets.cmake
#   --build-dir   build folder (default: build-fuzz/ in the repository)
#   --no-build    run the targets as they were last built
# Seeds: fuzz/corpus/<target>/, the regression inputs tests/data/fuzz/<target>/, the built-in
# scenarios (scenario) and the α³-Bench public episodes in $A3_SHARED_DIR/alphabench (episode;
# read where they are, never copied). New inputs go to <build-dir>/corpus/<target>/, findings to
# <build-dir>/findings/<target>/, each run's log to <build-dir>/logs/<target>.log.
# A3_BUILD_LOCK=FILE runs the build step under flock FILE (a build machine shared by several).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build_dir="$repo/build-fuzz"
seconds=60
runs=""
build=1
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs=$2; shift ;;
    --target) targets+=("$2"); shift ;;
    --build-dir) build_dir=$2; shift ;;
    --no-build) build=0 ;;
    -h|--help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    [0-9]*) seconds=$1 ;;
    *) echo "fuzz.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
shared_dir=${A3_SHARED_DIR:-$repo/../shared}
if [ ${#targets[@]} = 0 ]; then
  read -r -a targets <<<"$(sed -n 's/^set(A3_FUZZ_TARGETS \(.*\))$/\1/p' "$repo/fuzz/targets.cmake")"
fi

configure_and_build() {
  local cc cxx
  cxx=$(command -v clang++ || command -v clang++-14 || true)
  cc=$(command -v clang || command -v clang-14 || true)
  if [ -z "$cxx" ]; then
    echo "fuzz.sh: clang++ not found (Debian packages clang and libclang-rt-dev; scripts/setup.sh installs them)" >&2
    exit 2
  fi
  if [ ! -f "$build_dir/CMakeCache.txt" ]; then
    echo "fuzz.sh: configuring $build_dir ($cxx, -O1 -g, A3_FUZZ=ON)"
    cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx" \
      -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DA3_FUZZ=ON -DA3_WERROR=OFF \
      -DA3_BUILD_TESTS=OFF -DA3_BUILD_BENCH=OFF >/dev/null
  fi
  local lock=()
  [ -n "${A3_BUILD_LOCK:-}" ] && lock=(flock "$A3_BUILD_LOCK")
  echo "fuzz.sh: building the fuzz targets"
  local started=$SECONDS
  "${lock[@]}" nice -n 19 cmake --build "$build_dir" -j "${A3_FUZZ_JOBS:-2}" \
    --target $(printf 'fuzz_%s ' "${targets[@]}") >"$build_dir/build.log" 2>&1 ||
    { tail -n 40 "$build_dir/build.log" >&2; exit 2; }
  echo "fuzz.sh: built in $((SECONDS - started)) s"
}

# The seed folders of a target that exist (libFuzzer reads them recursively).
seed_dirs() {
  local name=$1
  local dirs=("$repo/fuzz/corpus/$name" "$repo/tests/data/fuzz/$name")
  [ "$name" = scenario ] && dirs+=("$repo/rigs/scenarios")
  [ "$name" = episode ] && dirs+=("$shared_dir/alphabench/eval_runs")
  for d in "${dirs[@]}"; do [ -d "$d" ] && echo "$d"; done
  return 0
}

# stat_of LOG NAME: the number libFuzzer's -print_final_stats gave for stat::NAME.
stat_of() { sed -n "s/^stat::$2: *\([0-9]*\)$/\1/p" "$1" | tail -n 1; }

run_target() {
  local name=$1
  local corpus="$build_dir/corpus/$name" findings="$build_dir/findings/$name" log="$build_dir/logs/$name.log"
  rm -rf "$findings"
  mkdir -p "$corpus" "$findings" "$(dirname "$log")"
  local budget=(-max_total_time="$seconds")
  [ -n "$runs" ] && budget=(-runs="$runs")
  local seeds
  mapfile -t seeds < <(seed_dirs "$name")
  local status=0
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:suppressions="$repo/fuzz/ubsan.supp" nice -n 19 "$build_dir/fuzz/fuzz_$name" \
    "${budget[@]}" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$findings/" "$corpus" "${seeds[@]}" >"$log" 2>&1 || status=$?
  local executions per_second cov new found
  executions=$(stat_of "$log" number_of_executed_units)
  per_second=$(stat_of "$log" average_exec_per_sec)
  new=$(stat_of "$log" new_units_added)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -n 1 | cut -d' ' -f2)
  found=$(find "$findings" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  printf '%-14s executions %9s  exec/s %6s  coverage %6s  new inputs %5s  findings %s%s\n' "$name" \
    "${executions:-?}" "${per_second:-?}" "${cov:-?}" "${new:-?}" "$found" \
    "$([ "$status" = 0 ] || echo "  (exit $status, see $log)")"
  find "$findings" -type f | sed 's/^/  finding: /'
  [ "$found" = 0 ] && [ "$status" = 0 ]
}

[ "$build" = 1 ] && configure_and_build
[ -d "$shared_dir/alphabench" ] || echo "fuzz.sh: $shared_dir/alphabench not found: the episode target starts from our seeds only"
failed=0
for name in "${targets[@]}"; do
  run_target "$name" || failed=1
done
exit "$failed"
