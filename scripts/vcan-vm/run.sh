#!/bin/sh
# Runs a shell command as root inside a small QEMU virtual machine that has real SocketCAN,
# with vcan0 up, in the host's current directory, and exits with the command's status.
# The guest boots Debian's generic kernel under TCG software emulation (see
# ../../../shared/vcan-vm.md for why: no usable KVM here), sees the host's / read-only over
# 9p with a throw-away tmpfs overlay (so host-built programs run unmodified; writes vanish),
# and reports the exit status on the serial console.
#
# Usage: scripts/vcan-vm/run.sh '<shell command>'
# Exit status: the command's; 77 when QEMU or the kernel cannot be had here (the message
# says why: callers such as CTest count that as skipped); 125 when the guest gave no status
# (crash or timeout).
# Environment:
#   A3_VCAN_VM_DIR      cache for the kernel and initramfs (default ~/.cache/a3rig/vcan-vm)
#   A3_VCAN_VM_ENV      names of host variables to pass into the guest (it starts from env -i)
#   A3_VCAN_VM_RW       a host folder (no spaces) the guest may write to (results, logs)
#   A3_VCAN_VM_TIMEOUT  seconds before the guest is killed (default 300)
#   A3_VCAN_VM_MEM, A3_VCAN_VM_SMP   guest memory (default 1024M) and CPUs (default 1)
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
DIR=${A3_VCAN_VM_DIR:-${HOME:-/root}/.cache/a3rig/vcan-vm}
say() { echo "vcan-vm: $*" >&2; }
[ $# -eq 1 ] || { say "usage: $0 '<shell command>'"; exit 2; }

command -v qemu-system-x86_64 >/dev/null 2>&1 || {
  say "QEMU is not installed (Debian package qemu-system-x86; scripts/setup.sh installs it)"
  exit 77
}
"$HERE/setup.sh" "$DIR" || exit $?

RUNS="$DIR/runs"
mkdir -p "$RUNS"
WORK=$(mktemp -d "$RUNS/run.XXXXXX")
trap 'rm -rf "$WORK"' EXIT INT TERM
TAG=$(basename "$WORK" | tr -dc 'A-Za-z0-9')

# The script the guest runs: the chosen variables, the current directory, the command.
{
  for name in ${A3_VCAN_VM_ENV:-}; do
    eval "set_=\${$name+x}"
    if [ -n "$set_" ]; then
      eval "value=\$$name"
      printf "export %s='%s'\n" "$name" "$(printf '%s' "$value" | sed "s/'/'\\\\''/g")"
    fi
  done
  printf "cd '%s' || exit 98\n" "$(pwd | sed "s/'/'\\\\''/g")"
  printf '%s\n' "$1"
} > "$WORK/cmd.sh"

FS="-fsdev local,id=hostroot,path=/,security_model=none,readonly=on,multidevs=remap"
FS="$FS -device virtio-9p-pci,fsdev=hostroot,mount_tag=hostroot"
APPEND_RW=
if [ -n "${A3_VCAN_VM_RW:-}" ]; then
  RWD=$(cd "$A3_VCAN_VM_RW" && pwd -P)
  FS="$FS -fsdev local,id=rwdir,path=$RWD,security_model=none,multidevs=remap"
  FS="$FS -device virtio-9p-pci,fsdev=rwdir,mount_tag=rwdir"
  APPEND_RW="a3_rw=$RWD"
fi

# -M pc, not microvm: microvm hangs in some boots under TCG (no fallback timer).
set +e
# shellcheck disable=SC2086
timeout "${A3_VCAN_VM_TIMEOUT:-300}" qemu-system-x86_64 -accel tcg -cpu qemu64 -M pc $FS \
  -m "${A3_VCAN_VM_MEM:-1024M}" -smp "${A3_VCAN_VM_SMP:-1}" \
  -nodefaults -no-user-config -display none -serial stdio -monitor none -no-reboot \
  -kernel "$DIR/vmlinux" -initrd "$DIR/initramfs.cpio.gz" \
  -append "console=ttyS0 quiet loglevel=1 panic=-1 mitigations=off cryptomgr.notests a3_cmd=$WORK/cmd.sh a3_tag=$TAG $APPEND_RW" \
  < /dev/null 2>&1 | tee "$WORK/console.log" | tr -d '\r' |
  grep -av -e "A3VM_EXIT_$TAG=" -e "reboot: Power down"
set -e
rc=$(tr -d '\r' < "$WORK/console.log" | sed -n "s/.*A3VM_EXIT_$TAG=\([0-9][0-9]*\)\$/\1/p" | tail -n1)
if [ -z "$rc" ]; then
  say "the guest gave no exit status (crashed, or killed after ${A3_VCAN_VM_TIMEOUT:-300} s)"
  exit 125
fi
exit "$rc"
