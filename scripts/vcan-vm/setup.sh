#!/bin/sh
# Prepares the vcan test VM once: fetches Debian's generic amd64 kernel (apt-get download, not
# installed), unpacks the uncompressed vmlinux and builds a busybox initramfs with the CAN,
# 9p and overlay modules. Idempotent; the result is cached outside the repository.
# Usage: scripts/vcan-vm/setup.sh [cache dir]   (default $A3_VCAN_VM_DIR or ~/.cache/a3rig/vcan-vm)
# Exit status: 0 ready, 77 cannot be prepared here (message on stderr says why).
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
DIR=${1:-${A3_VCAN_VM_DIR:-${HOME:-/root}/.cache/a3rig/vcan-vm}}
say() { echo "vcan-vm setup: $*" >&2; }
cannot() { say "$*"; exit 77; }

for tool in qemu-system-x86_64 busybox apt-get apt-cache dpkg-deb gzip cpio python3; do
  case $tool in
    busybox) [ -x /bin/busybox ] || cannot "/bin/busybox missing (apt-get install busybox-static)";;
    cpio) ;; # busybox provides cpio
    *) command -v "$tool" >/dev/null 2>&1 || cannot "$tool not found (qemu-system-x86 / apt tools needed)";;
  esac
done
file -L /bin/busybox 2>/dev/null | grep -q 'dynamically linked' && \
  cannot "/bin/busybox is dynamically linked; the initramfs needs busybox-static"

mkdir -p "$DIR"
cd "$DIR"
# Debian's generic kernel (the cloud flavour has neither CAN nor 9p).
KPKG=$(apt-cache depends linux-image-amd64 2>/dev/null | sed -n 's/.*Depends: \(linux-image-[0-9].*-amd64\)$/\1/p' | head -n1)
[ -n "$KPKG" ] || cannot "apt-cache knows no linux-image-amd64 (run apt-get update?)"
if [ -f vmlinux ] && [ -f initramfs.cpio.gz ] && [ "$(cat kernel-package 2>/dev/null)" = "$KPKG" ]; then
  exit 0
fi
say "preparing $KPKG in $DIR"
mkdir -p debs
if ! ls debs/"$KPKG"_*.deb >/dev/null 2>&1; then
  (cd debs && apt-get download -q "$KPKG" >/dev/null 2>&1) || \
    (apt-get update -qq >/dev/null 2>&1 && cd debs && apt-get download -q "$KPKG" >/dev/null 2>&1) || \
    cannot "apt-get download $KPKG failed (no access to the Debian archive?)"
fi
rm -rf kroot && mkdir kroot
dpkg-deb -x debs/"$KPKG"_*.deb kroot
# Boot the uncompressed ELF (PVH entry): skips the slow in-guest xz decompression under TCG.
python3 - kroot/boot/vmlinuz-* vmlinux.tmp <<'PY'
import lzma, sys
data = open(sys.argv[1], 'rb').read()
offset = data.find(b'\xfd7zXZ\x00')
if offset < 0:
    sys.exit("vcan-vm setup: no xz payload in " + sys.argv[1])
open(sys.argv[2], 'wb').write(lzma.LZMADecompressor().decompress(data[offset:]))
PY
"$HERE/build-initramfs.sh" kroot initramfs.cpio.gz.tmp
mv vmlinux.tmp vmlinux
mv initramfs.cpio.gz.tmp initramfs.cpio.gz
rm -rf kroot
echo "$KPKG" > kernel-package
say "ready: $DIR/vmlinux, $DIR/initramfs.cpio.gz"
