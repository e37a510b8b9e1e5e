#!/usr/bin/env bash
# Runs the real-time tests N times (default 20) under `ctest -j2` with the vcan QEMU test
# running beside them (the heaviest neighbour the suite has), and prints how often each passed.
# Not part of CI: with every real-time test (the default) one run takes about 15 minutes;
# A3_STRESS_TESTS='RealTimeRig|vcan' (a ctest -R pattern) picks fewer. Needs a build
# (scripts/setup.sh) and, as root, scripts/lcm-loopback.sh. Usage: scripts/stress-realtime.sh [N]
set -uo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${A3_BUILD_DIR:-$repo/build}
runs=${1:-20}
export A3_SHARED_DIR=${A3_SHARED_DIR:-$repo/../shared}
[ "$(id -u)" = 0 ] && "$repo/scripts/lcm-loopback.sh" >/dev/null
# The real-time tests, and the vcan VM tests as their neighbour.
pattern=${A3_STRESS_TESTS:-'RealTimeRig|LockstepUnderLoad|LockstepFaults|RealTimeLoop|ToolServerRealTime|RunCommand|LinkEmulatorRealTime|vcan'}
declare -A passed failed
for i in $(seq 1 "$runs"); do
  log=$(mktemp)
  ctest --test-dir "$build_dir" -j2 -R "$pattern" --output-on-failure >"$log" 2>&1
  while read -r name result; do
    if [ "$result" = Passed ]; then passed[$name]=$(( ${passed[$name]:-0} + 1 ));
    else failed[$name]=$(( ${failed[$name]:-0} + 1 )); fi
  done < <(sed -n 's/^ *[0-9]*\/[0-9]* Test *#[0-9]*: \([^ ]*\) \.*[* ]*\([A-Za-z]*\).*/\1 \2/p' "$log")
  echo "run $i/$runs: $(grep -c 'Passed' "$log") passed, $(grep -cE 'Failed|Timeout' "$log") failed"
  rm -f "$log"
done
echo "passes out of $runs runs (ctest -j2, the vcan VM test beside the real-time tests):"
for name in $(printf '%s\n' "${!passed[@]}" "${!failed[@]}" | sort -u); do
  printf '  %-90s %d/%d\n' "$name" "${passed[$name]:-0}" "$runs"
done
