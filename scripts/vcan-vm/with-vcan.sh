#!/bin/sh
# Runs a shell command where a real SocketCAN vcan0 is up: directly when this machine's
# kernel has vcan (creating vcan0 when it is missing and we are root), otherwise inside the
# QEMU virtual machine of run.sh. For tests that need real SocketCAN (CTest label "vcan").
# Usage: scripts/vcan-vm/with-vcan.sh '<shell command>'
# Exit status: the command's; 77 when neither way is possible here (the message says why).
# Set A3_VCAN_FORCE_VM=1 to use the VM even where the host has vcan.
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
[ $# -eq 1 ] || { echo "usage: $0 '<shell command>'" >&2; exit 2; }

host_vcan() {
  [ "${A3_VCAN_FORCE_VM:-0}" = 1 ] && return 1
  command -v ip >/dev/null 2>&1 || return 1
  if ip link show vcan0 >/dev/null 2>&1; then
    ip link show vcan0 | grep -q 'state UNKNOWN\|state UP\|,UP' && return 0
    [ "$(id -u)" = 0 ] && ip link set up vcan0 2>/dev/null && return 0
    return 1
  fi
  [ "$(id -u)" = 0 ] || return 1
  modprobe vcan 2>/dev/null || true
  ip link add dev vcan0 type vcan 2>/dev/null && ip link set up vcan0 2>/dev/null
}

if host_vcan; then
  echo "with-vcan: this kernel has vcan: running on the host's vcan0" >&2
  exec /bin/sh -c "$1"
fi
echo "with-vcan: no vcan on this kernel: running in the QEMU virtual machine (software emulation)" >&2
exec "$HERE/run.sh" "$1"
