# A one-node Slurm cluster on localhost for tests (sourced, not run): munged, slurmctld and
# slurmd with a configuration in a folder of the caller's own, per /work/shared/slurm-local.md.
# slurm_cluster_start D   writes D/slurm.conf, starts the daemons, exports SLURM_CONF, waits
#                         for the node to be idle; returns 1 (with a message) when it is not.
# slurm_cluster_stop D    stops the daemons it started (their pid files), munged last if it
#                         was started here. Safe to call twice and after a failed start.

slurm_cluster_conf() {
  d=$1
  host=$(hostname -s)
  cat <<EOF
ClusterName=a3test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/ctld.log
SlurmdLogFile=$d/d.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SlurmctldPort=16817
SlurmdPort=16818
MpiDefault=none
ReturnToService=2
NodeName=$host CPUs=2 State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
}

slurm_munge_start() {
  d=$1
  if munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then return 0; fi  # a munged runs already
  if [ ! -f /etc/munge/munge.key ]; then
    dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 2>/dev/null
    chown munge:munge /etc/munge/munge.key && chmod 400 /etc/munge/munge.key
  fi
  mkdir -p /run/munge && chown munge:munge /run/munge
  /usr/sbin/munged --force || return 1
  touch "$d/munged.started-here"
  munge -n | unmunge | grep -q 'STATUS: *Success' || { echo "munge does not work (munge -n | unmunge)"; return 1; }
}

slurm_cluster_start() {
  d=$1
  mkdir -p "$d/state" "$d/spool"
  slurm_cluster_conf "$d" >"$d/slurm.conf"
  export SLURM_CONF="$d/slurm.conf"
  slurm_munge_start "$d" || return 1
  slurmctld -f "$SLURM_CONF" || { echo "slurmctld did not start: $(tail -5 "$d/ctld.log" 2>/dev/null)"; return 1; }
  slurmd -f "$SLURM_CONF" || { echo "slurmd did not start: $(tail -5 "$d/d.log" 2>/dev/null)"; return 1; }
  for _ in $(seq 1 60); do
    if sinfo -h -o '%t' 2>/dev/null | grep -q '^idle'; then return 0; fi
    sleep 1
  done
  echo "the node did not become idle in 60 s: $(sinfo 2>&1)"
  tail -5 "$d/ctld.log" "$d/d.log" 2>/dev/null
  return 1
}

slurm_stop_pid_file() {
  f=$1
  [ -f "$f" ] || return 0
  pid=$(cat "$f")
  [ -n "$pid" ] && kill "$pid" 2>/dev/null
  for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  kill -9 "$pid" 2>/dev/null
  rm -f "$f"
}

slurm_cluster_stop() {
  d=$1
  slurm_stop_pid_file "$d/slurmd.pid"
  slurm_stop_pid_file "$d/slurmctld.pid"
  if [ -f "$d/munged.started-here" ]; then
    slurm_stop_pid_file /run/munge/munged.pid
    rm -f "$d/munged.started-here"
  fi
}
