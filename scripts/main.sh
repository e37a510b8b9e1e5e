#!/usr/bin/env bash
# The main job: installs the Debian packages the a3rig program needs, builds that program only
# (scripts/test.sh installs and builds the rest), and flies one conversational mission in
# real time with the built-in (scripted) agent: `a3rig run` on the survey-field scenario
# (about 4 minutes of wall time), writing out/run/episode.json (α³-Bench format), the LCM log
# and a trajectory plot, and printing the score. Extra arguments go to `a3rig run`, e.g.
#   scripts/main.sh --scenario traffic-conflict --think-time 30 --rtf 4
# As root it routes LCM's multicast group over loopback first (the rig's nodes talk LCM UDP).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
install=()
[ "$(id -u)" = 0 ] || install=(--no-install)
"$repo/scripts/setup.sh" --program-only "${install[@]}"
if [ "$(id -u)" = 0 ]; then
  "$repo/scripts/lcm-loopback.sh"
fi
export A3_SHARED_DIR=${A3_SHARED_DIR:-$repo/../shared}
mkdir -p "$repo/out"
exec "$repo/build/a3rig" run --scenario survey-field --out "$repo/out/run" "$@"
