#!/usr/bin/env bash
# A newcomer's first flight, timed: a fresh clone of this repository through the main job's
# steps (scripts/setup.sh --program-only: install, configure, build the a3rig program), then a
# short real-time flight, then one .cpp file touched, rebuilt and flown again in virtual time.
# Prints one line per phase with its wall time. On a machine where the packages are already
# installed the install phase only checks them; the README's figure says which it was.
# Usage: bench/setup/first_flight.sh [WORK_DIR]   (default: a new folder under /tmp)
#   A3_FLIGHT_ARGS   the flight's arguments (default: --scenario traffic-conflict --rtf 4)
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
work=${1:-$(mktemp -d /tmp/a3rig-first-flight-XXXXXX)}
flight_args=${A3_FLIGHT_ARGS:---scenario traffic-conflict --rtf 4}
now() { date +%s.%N; }
span() { python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):8.1f} s')" "$1" "$2"; }

t_clone=$(now)
git clone -q "$repo" "$work/a3rig"
clone=$(span "$t_clone" "$(now)")
cd "$work/a3rig"

# setup.sh's own progress lines mark its phases: installing, configuring, building, done.
declare -A mark
install_flag=()
[ "$(id -u)" = 0 ] || install_flag=(--no-install)
mark[start]=$(now)
while IFS= read -r line; do
  case "$line" in
    "setup.sh: configuring"*) mark[configure]=$(now) ;;
    "setup.sh: building"*) mark[build]=$(now) ;;
    "setup.sh: done"*) mark[done]=$(now) ;;
  esac
done < <(scripts/setup.sh --program-only "${install_flag[@]}" 2>&1)
[ -n "${mark[done]:-}" ] || { echo "first_flight: scripts/setup.sh failed (run it by hand in $work/a3rig)" >&2; exit 1; }

[ "$(id -u)" = 0 ] && scripts/lcm-loopback.sh > /dev/null
t_flight=$(now)
# shellcheck disable=SC2086
build/a3rig run $flight_args --out "$work/out/flight" --quiet > "$work/flight.log" 2>&1
t_flown=$(now)

touch rigs/cli/cmd_report.cpp
t_edit=$(now)
cmake --build build --target a3rig > "$work/rebuild.log" 2>&1
t_rebuilt=$(now)
build/a3rig run --scenario traffic-conflict --runtime virtual --out "$work/out/again" --quiet > "$work/again.log" 2>&1
t_again=$(now)

echo "first flight, $(nproc) cores, $(date -u +%F), $(. /etc/os-release; echo "$PRETTY_NAME")"
echo "  clone                          $clone"
echo "  install (apt-get)              $(span "${mark[start]}" "${mark[configure]}")"
echo "  configure (cmake)              $(span "${mark[configure]}" "${mark[build]}")"
echo "  build (a3rig only)             $(span "${mark[build]}" "${mark[done]}")"
echo "  flight ($flight_args)  $(span "$t_flight" "$t_flown")"
echo "  clone to end of flight         $(span "$t_clone" "$t_flown")"
echo "  one .cpp edited: rebuild       $(span "$t_edit" "$t_rebuilt")"
echo "  and fly again (virtual time)   $(span "$t_rebuilt" "$t_again")"
echo "  (work folder: $work)"
