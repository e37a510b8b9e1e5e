#!/bin/sh
# Prints the CAN figures of bridge/README.md: codec cost per frame, frame-length cost, and the sustained frame
# rate without loss between two processes on the userspace bus and on vcan0 (on the host
# when its kernel has vcan, else inside the QEMU VM: software emulation, far slower than
# real hardware).
# Usage: bench/bridge/run_can_benchmarks.sh [build dir]   (default: build/)
set -eu
repo=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$repo/build}" && pwd)
echo "== DroneCAN codec, per frame (items_per_second = frames)"
"$build/bench/bench_dronecan_codec" --benchmark_min_time=0.5
echo
echo "== exact frame length (CRC-15, stuffing), per frame: bit-by-bit reference vs table-driven"
"$build/bench/bench_can_frame_bits" --benchmark_min_time=0.5
echo
echo "== userspace CAN bus"
"$build/bench/bench_can_throughput" --bus userspace:a3bench --seconds 2
echo
echo "== vcan0 (SocketCAN)"
set +e
"$repo/scripts/vcan-vm/with-vcan.sh" \
  "$build/bench/bench_can_throughput --bus vcan0 --seconds 2 --rates 5000,10000,20000,50000,max"
rc=$?
set -e
[ "$rc" = 77 ] && echo "(skipped: no vcan on this kernel and no QEMU VM)"
exit 0
