#!/usr/bin/env bash
# Resident memory of the dynamics node as its own process: runs `a3rig node dynamics` in real
# time with its built-in climb demo publishing rotor commands (so it integrates and publishes
# at 100 Hz), samples /proc/PID/status while it runs, and prints the last VmRSS and the peak
# (VmHWM). Usage: bench/dynamics/node_rss.sh [BUILD_DIR] [SECONDS] [INTEGRATOR]
#   defaults: build/ in the repository, 10 s, rk4
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
build=${1:-$repo/build}
seconds=${2:-10}
integrator=${3:-rk4}
# A port of its own: this run neither hears nor disturbs other LCM runs on the host.
"$build/a3rig" node dynamics --integrator "$integrator" --demo climb --duration-s "$seconds" \
  --report-every-s 1000 --lcm-url 'udpm://239.255.76.67:7692?ttl=0' 2>/dev/null &
pid=$!
rss="" hwm=""
while kill -0 "$pid" 2>/dev/null; do
  if status=$(cat "/proc/$pid/status" 2>/dev/null); then
    r=$(awk '/^VmRSS:/ {print $2}' <<<"$status")
    h=$(awk '/^VmHWM:/ {print $2}' <<<"$status")
    [ -n "$r" ] && rss=$r
    [ -n "$h" ] && hwm=$h
  fi
  sleep 0.2
done
wait "$pid" || { echo "node_rss.sh: a3rig node dynamics failed" >&2; exit 1; }
awk -v i="$integrator" -v s="$seconds" -v r="$rss" -v h="$hwm" 'BEGIN {
  printf "a3rig node dynamics (%s, %s s of the climb demo at 100 Hz): VmRSS %.1f MB, peak VmHWM %.1f MB\n", i, s, r / 1024, h / 1024 }'
