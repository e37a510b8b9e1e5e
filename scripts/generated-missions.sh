#!/usr/bin/env bash
# Flies N generated missions per difficulty (easy, medium, hard) with the scripted agent in
# virtual time through `a3rig sweep --scenarios gen:N:<difficulty>` (parallel, with progress,
# resumable), then prints the success rate per difficulty, how many failures were the agent's
# own (results.csv agent_failure) and the missions that failed.
#   scripts/generated-missions.sh [N=20] [extra a3rig sweep arguments, e.g. -j 2 --agents llm]
# Output: out/generated-missions/<difficulty>/ (results.csv, cells/gen_<seed>_<difficulty>/...).
set -euo pipefail
cd "$(dirname "$0")/.."
n="${1:-20}"
shift || true
a3rig="${A3RIG:-build/a3rig}"
out="${A3_GENERATED_OUT:-out/generated-missions}"
[[ -x "$a3rig" ]] || { echo "generated-missions.sh: $a3rig not built (scripts/test.sh or cmake --build build)" >&2; exit 2; }
[[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "generated-missions.sh: N must be a positive integer, got '$n'" >&2; exit 2; }

mkdir -p "$out"
summary=()
for difficulty in easy medium hard; do
  echo "== $difficulty: $n generated missions (gen:$n:$difficulty)" >&2
  # Exit status 1 (some cell failed to produce an episode) is reported below, not fatal.
  "$a3rig" sweep --scenarios "gen:$n:$difficulty" --agents scripted --think-times 0 --slices URLLC --seeds 1 \
    --out "$out/$difficulty" "$@" >"$out/$difficulty.log" || true
  line=$(awk -F, -v d="$difficulty" '
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    { total++; if ($col["success"] == "true" || $col["success"] == "1") ok++; else failed = failed " " $col["scenario"]
      if ($col["agent_failure"] == "1") agent++ }
    END { printf "%-6s %3d / %3d succeeded (%5.1f %%), %d failed by a fault of the agent%s", d, ok, total,
          total ? 100 * ok / total : 0, agent, failed == "" ? "" : "; failed:" failed }' "$out/$difficulty/results.csv")
  echo "$line"
  summary+=("$line")
done
echo "== success rate per difficulty (scripted agent, virtual time)"
printf '%s\n' "${summary[@]}"
