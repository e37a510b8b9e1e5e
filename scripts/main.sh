#!/usr/bin/env bash
# The main job: installs the Debian packages, builds, and scores the α³-Bench public episodes
# in ../shared/alphabench (or $A3_SHARED_DIR/alphabench), printing the leaderboard, the
# per-episode rows and the figures into out/. Extra arguments go to `a3rig score`.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
install=()
[ "$(id -u)" = 0 ] || install=(--no-install)
"$repo/scripts/setup.sh" "${install[@]}"
shared=${A3_SHARED_DIR:-$repo/../shared}
corpus="$shared/alphabench/eval_runs"
if [ ! -d "$corpus" ]; then
  echo "main.sh: $corpus not found: get the α³-Bench public release (repository maferrag/AlphaBench," >&2
  echo "main.sh: folder Results_Evaluation/eval_runs) and put it there, or set A3_SHARED_DIR" >&2
  exit 2
fi
mkdir -p "$repo/out"
exec "$repo/build/a3rig" score "$corpus" --per-episode "$repo/out/episodes.csv" --plots "$repo/out/figures" "$@"
