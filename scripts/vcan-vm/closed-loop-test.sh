#!/bin/sh
# The real-vcan closed-loop test: dynamics, bridge, fc, a DroneCAN frame monitor and candump
# as separate processes, the bridge and fc on a real SocketCAN vcan0, LCM (udpm, ttl=0) between
# the dynamics, the bridge and a ground station that flies a short mission (take off to 5 m,
# hold, 10 m east, land). Run where vcan0 is up: through with-vcan.sh (the host's vcan0, or the
# QEMU VM of run.sh), e.g.
#   scripts/vcan-vm/with-vcan.sh "A3RIG=build/a3rig GROUND=build/tests/bridge_nodes_vcan_ground \
#       MONITOR=build/tests/bridge_nodes_can_monitor sh scripts/vcan-vm/closed-loop-test.sh"
# Environment: A3RIG, GROUND, MONITOR (programs, required); A3_LOOP_RTF (real-time factor:
# default 1 on a host, 0.25 inside the VM, whose software emulation cannot keep five processes
# and ~2,200 frames/s at full speed: see bridge/nodes/README.md);
# A3_LOOP_LCM_URL (default udpm://239.255.76.67:7681?ttl=0: a port of its own, so other rigs
# on the host do not cross-talk). Exit status: 0 passed, 1 failed, 77 cannot run here.
set -u
if grep -q 'a3_cmd=' /proc/cmdline 2>/dev/null; then RTF=${A3_LOOP_RTF:-0.25}; else RTF=${A3_LOOP_RTF:-1}; fi
URL=${A3_LOOP_LCM_URL:-udpm://239.255.76.67:7681?ttl=0}
say() { echo "closed-loop-test: $*"; }
for v in A3RIG GROUND MONITOR; do
  eval "p=\${$v:-}"
  [ -n "$p" ] && [ -x "$p" ] || { say "$v must name the program (got '$p')"; exit 1; }
done
command -v candump >/dev/null 2>&1 || { say "candump not found (Debian package can-utils)"; exit 77; }
ip link show vcan0 >/dev/null 2>&1 || { say "no vcan0 here"; exit 77; }

# LCM multicast must loop back on lo (the VM's lo has neither multicast nor the route).
if ! ip route show 239.255.76.67 2>/dev/null | grep -q 'dev lo'; then
  if [ "$(id -u)" = 0 ]; then
    ip link set lo multicast on && ip route add 239.255.76.67/32 dev lo ||
      { say "cannot route LCM multicast over lo"; exit 77; }
  else
    say "LCM multicast is not routed over lo and we are not root (scripts/lcm-loopback.sh)"; exit 77
  fi
fi

T=$(mktemp -d /tmp/a3-closed-loop.XXXXXX)
PIDS=
start() {  # start NAME COMMAND...: runs in the background, output to $T/NAME.log
  name=$1; shift
  "$@" > "$T/$name.log" 2>&1 &
  PIDS="$PIDS $!"
  eval "PID_$name=$!"
}
stop_all() {
  for p in $PIDS; do kill -TERM "$p" 2>/dev/null; done
  for p in $PIDS; do wait "$p" 2>/dev/null; done
}
trap 'stop_all; rm -rf "$T"' EXIT INT TERM

say "real-time factor $RTF, LCM $URL, logs in $T"
START=$(date +%s)
# candump for the first 20000 frames (~10 s of flight): printing every frame of the whole
# mission would cost the emulated machine more than the rig itself.
start candump candump -L -n 20000 vcan0
start monitor "$MONITOR" --can socketcan:vcan0 --rtf "$RTF"
start dynamics "$A3RIG" node dynamics --rate-hz 250 --rtf "$RTF" --lcm-url "$URL" --report-every-s 5
start bridge "$A3RIG" node bridge --can socketcan:vcan0 --rtf "$RTF" --lcm-url "$URL" --report-every-s 5
start fc "$A3RIG" node fc --can socketcan:vcan0 --rtf "$RTF" --report-every-s 5
"$GROUND" --lcm-url "$URL" --rtf "$RTF"
ground=$?
# Stop the nodes (the monitor prints its counts on SIGTERM), then look at what was seen.
kill -TERM "$PID_dynamics" "$PID_bridge" "$PID_fc" "$PID_candump" 2>/dev/null
wait "$PID_dynamics" "$PID_bridge" "$PID_fc" "$PID_candump" 2>/dev/null
kill -TERM "$PID_monitor" 2>/dev/null
wait "$PID_monitor"
monitor=$?
PIDS=
cat "$T/monitor.log"

# candump must have seen the frames too: DroneCAN IDs carry the data type ID in bits 8..23 and
# the source node in bits 0..6 (fc 10 = 0A, bridge 20 = 14).
dump=0
check_dump() {  # check_dump WHAT DTID_HEX NODE_HEX MIN
  n=$(grep -ci " vcan0 ..$2$3#" "$T/candump.log")
  if [ "$n" -ge "$4" ]; then r=ok; else r=MISSING; dump=1; fi
  say "candump: $n frames of $1 (data type 0x$2 from node 0x$3) $r"
}
check_dump esc.RawCommand 0406 0A 1000
check_dump ahrs.RawIMU 03EB 14 1000
check_dump gnss.Fix2 0427 14 50
check_dump a3.fc.Command 5078 14 20
check_dump a3.fc.Status 5079 0A 50
check_dump NodeStatus 0155 0A 5
check_dump NodeStatus 0155 14 5
say "candump saw $(wc -l < "$T/candump.log") frames in all"

status=0
[ "$ground" = 0 ] || { status=1; say "the mission failed (ground exit $ground)"; }
[ "$ground" = 77 ] && status=77
[ "$monitor" = 0 ] || { status=1; say "the monitor's checks failed"; }
[ "$dump" = 0 ] || status=1
lines=4
[ "$status" != 0 ] && lines=15
for n in dynamics bridge fc; do say "--- $n log (tail)"; tail -n $lines "$T/$n.log"; done
say "took $(( $(date +%s) - START )) s of wall time; $( [ $status = 0 ] && echo PASSED || echo FAILED )"
exit $status
