#!/usr/bin/env bash
# Runs every dynamics benchmark and prints its figures (see README.md beside this file):
# virtual-time speed (RK4, ARKODE ERK, CVODE, ODE, calm and turbulent) with solver statistics, the SciPy
# baseline on the same flight, real-time jitter and achieved real-time factor under CPU load,
# the node's resident memory, and the trajectory plot (docs/figures/dynamics_flight.png).
# Usage: bench/dynamics/run_all.sh [--quick] [BUILD_DIR]
#   --quick   short runs (60 simulated s, 10 s real time) for a look, not for the README
#   BUILD_DIR default: build/ in the repository (configured with benchmarks, the default)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
quick=0
build="$repo/build"
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    -h|--help) sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) build=$arg ;;
  esac
done
cmake --build "$build" --target bench_dynamics_virtual bench_dynamics_realtime bench_dynamics_flight a3rig >/dev/null
# Debian's Python, where python3-scipy installs (a python3 earlier on PATH may lack it).
python=/usr/bin/python3
[ -x "$python" ] || python=python3
sim_s=600; rt_s=60; py_s=60
if [ "$quick" = 1 ]; then sim_s=60; rt_s=10; py_s=10; fi
csv=$(mktemp --suffix=.csv)
log=$(mktemp)
trap 'rm -f "$csv" "$log"' EXIT

echo "== 1. virtual time: simulated seconds per wall second"
"$build/bench/bench_dynamics_virtual" --sim-s "$sim_s" --csv "$csv" --csv-s $((12 + py_s + 1)) 2>/dev/null | tee "$log"
cvode_rtf=$(awk '/^cvode calm / {sub("x", "", $3); print $3}' "$log")
cvode_cpu_rtf=$(awk '/^cvode calm / {sub("x", "", $4); print $4}' "$log")

echo
echo "== 2. the same equations in Python (SciPy solve_ivp), same flight"
"$python" "$here/scipy_model.py" "$csv" --duration-s "$py_s" --cpp-rtf "$cvode_rtf" --cpp-cpu-rtf "$cvode_cpu_rtf"

echo
echo "== 3. real time at factor 1 with a CPU-burning process"
"$build/bench/bench_dynamics_realtime" --duration-s "$rt_s" 2>/dev/null

echo
echo "== 4. resident memory of the node"
"$here/node_rss.sh" "$build" 10

echo
echo "== 5. trajectory plot"
"$here/plot_flight.sh" "$build" 2>/dev/null
