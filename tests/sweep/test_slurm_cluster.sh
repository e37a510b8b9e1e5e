#!/bin/bash
# `a3rig sweep --slurm` on a real one-node Slurm cluster (Debian's slurm-wlm and munge, as in
# /work/shared/slurm-local.md): installs them when missing, starts munged, slurmctld and slurmd on
# localhost with a configuration in a temporary folder, submits a 12-cell sweep (job array + merge
# job), waits for the merge, checks that results.csv equals the same sweep run locally (every
# column but the wall time), and stops the daemons. Exit 77 (skip) when not root or when the
# packages cannot be installed.
# Usage: test_slurm_cluster.sh A3RIG WORK_DIR
set -u
a3rig=$1
work=$2
here=$(cd "$(dirname "$0")" && pwd)
skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }

[ "$(id -u)" = 0 ] || skip "the one-node Slurm cluster needs root (munged, slurmctld and slurmd as root)"
if ! command -v slurmctld >/dev/null 2>&1 || [ ! -x /usr/sbin/munged ]; then
  echo "installing slurm-wlm and munge (apt-get)"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq -o DPkg::Lock::Timeout=600 --no-install-recommends \
    slurm-wlm munge >/dev/null 2>&1 || skip "apt-get could not install slurm-wlm and munge (no Debian registry?)"
fi

rm -rf "$work"
mkdir -p "$work/cluster"
# shellcheck source=slurm_cluster.sh
. "$here/slurm_cluster.sh"
trap 'slurm_cluster_stop "$work/cluster"' EXIT
slurm_cluster_start "$work/cluster" || fail "the one-node cluster did not start (logs in $work/cluster)"
echo "cluster up: $(sinfo -h 2>&1 | head -1)"

# 2 think times x 3 slices x 2 seeds = 12 cells, the shortest built-in mission.
grid=(--scenarios parcel-delivery --think-times 0,20 --slices URLLC,eMBB,mMTC --seeds 1-2)
cd "$work" || fail "cannot enter $work"
submitted=$("$a3rig" sweep "${grid[@]}" --out slurm-out --slurm --array-parallelism 2) || fail "submission failed: $submitted"
echo "$submitted"
merge_job=$(sed -n 's/^slurm: .*merge job \([0-9]*\).*/\1/p' <<<"$submitted")
[ -n "$merge_job" ] || fail "no merge job id in the submission's output"

"$a3rig" sweep "${grid[@]}" --out local-out --jobs 2 >local.log 2>&1 || fail "the local sweep failed: $(tail -5 local.log)"

for _ in $(seq 1 600); do  # the merge job leaves the queue when it has ended
  squeue -h -j "$merge_job" 2>/dev/null | grep -q . || break
  sleep 1
done
squeue -h -j "$merge_job" 2>/dev/null | grep -q . && fail "the merge job $merge_job had not ended after 600 s: $(squeue 2>&1)"
[ -f slurm-out/results.csv ] || fail "no slurm-out/results.csv; merge log: $(cat slurm-out/slurm/logs/* 2>/dev/null | tail -20)"

# Every column but wall_time_s (it differs run to run), rows in the same order.
without_wall() {
  python3 -c '
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
drop = rows[0].index("wall_time_s")
for r in rows: print(",".join(v for i, v in enumerate(r) if i != drop))' "$1"
}
cells=$(($(wc -l <slurm-out/results.csv) - 1))
[ "$cells" = 12 ] || fail "slurm-out/results.csv has $cells rows, not 12"
if ! diff <(without_wall local-out/results.csv) <(without_wall slurm-out/results.csv); then
  fail "results.csv differs between Slurm and the local run (above)"
fi
[ -f slurm-out/index.html ] || fail "the merge job wrote no index.html"
echo "ok: 12 cells on Slurm (array + merge job $merge_job) give the local sweep's results.csv"
