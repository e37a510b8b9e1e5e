#!/usr/bin/env bash
# Flies the reference set of a redesign's "behaviour unchanged" check in virtual time: every
# built-in scenario and 30 generated missions (gen:1..30, medium), each into OUT/<name>/, with
# the given a3rig. Compare two such folders with bench/rigs/episode_diff.py BASE NEW.
# Usage: bench/rigs/fly_reference.sh A3RIG OUT
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 A3RIG OUT" >&2; exit 2; }
a3rig=$1 out=$2
mkdir -p "$out"
scenarios=(survey-field parcel-delivery bridge-inspection thermal-search nfz-detour traffic-conflict)
for seed in $(seq 1 30); do scenarios+=("gen:$seed:medium"); done
for scenario in "${scenarios[@]}"; do
  name=${scenario//:/-}
  "$a3rig" run -q --runtime virtual --scenario "$scenario" --no-lcm-log --no-plot --no-report \
    --out "$out/$name" > "$out/$name.log" 2>&1 || echo "$scenario: exit $? (see $out/$name.log)"
done
echo "fly_reference.sh: ${#scenarios[@]} episodes in $out"
