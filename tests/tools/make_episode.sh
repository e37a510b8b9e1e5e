#!/usr/bin/env bash
# Flies SCENARIO in virtual time into OUT (emptied first), for the tools tests to read its
# episode.lcmlog. Usage: make_episode.sh A3RIG OUT SCENARIO
set -euo pipefail
a3rig=$1 out=$2 scenario=$3
rm -rf "$out"
"$a3rig" run --runtime virtual --scenario "$scenario" --out "$out" --no-plot --quiet
test -s "$out/episode.lcmlog" || { echo "make_episode.sh: $out/episode.lcmlog was not written" >&2; exit 1; }
