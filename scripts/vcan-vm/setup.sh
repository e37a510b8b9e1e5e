#!/bin/sh
# Prepares the vcan test VM once: fetches Debian's generic amd64 kernel package (apt-get
# download: not installed), unpacks the uncompressed vmlinux and builds a busybox initramfs
# with the virtio, 9p, overlay and CAN modules and guest-init.sh as /init. Idempotent: the
# result is cached outside the repository and rebuilt only when the kernel package or the
# initramfs scripts change; a cached kernel is used without asking apt at all.
# Usage: scripts/vcan-vm/setup.sh [cache dir]   (default $A3_VCAN_VM_DIR or ~/.cache/a3rig/vcan-vm)
# Exit status: 0 ready, 77 cannot be prepared here (the message on stderr says why).
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
DIR=${1:-${A3_VCAN_VM_DIR:-${HOME:-/root}/.cache/a3rig/vcan-vm}}
say() { echo "vcan-vm setup: $*" >&2; }
cannot() { say "$*"; exit 77; }

[ -x /bin/busybox ] || cannot "/bin/busybox missing (Debian package busybox-static; scripts/setup.sh installs it)"
if command -v file >/dev/null 2>&1 && file -L /bin/busybox | grep -q 'dynamically linked'; then
  cannot "/bin/busybox is dynamically linked; the initramfs needs busybox-static"
fi
for tool in dpkg-deb gzip python3 sha256sum; do
  command -v "$tool" >/dev/null 2>&1 || cannot "$tool not found"
done

mkdir -p "$DIR" "$DIR/debs"
cd "$DIR"
# One preparation at a time: two vcan tests started together on a new machine must not unpack
# into the same folder at once (the second waits, then finds the cache ready).
if command -v flock >/dev/null 2>&1; then
  exec 9>"$DIR/.setup.lock"
  flock 9
fi
SCRIPTS_HASH=$(cat "$HERE/build-initramfs.sh" "$HERE/guest-init.sh" | sha256sum | cut -c1-16)

# Which kernel: the one cached, unless apt knows a newer linux-image-amd64 dependency.
KPKG=
if command -v apt-cache >/dev/null 2>&1; then
  KPKG=$(apt-cache depends linux-image-amd64 2>/dev/null |
         sed -n 's/.*Depends: \(linux-image-[0-9].*-amd64\)$/\1/p' | head -n1)
fi
CACHED=$(cat kernel-package 2>/dev/null || true)
[ -n "$KPKG" ] || KPKG=$CACHED
if [ -z "$KPKG" ] && command -v apt-get >/dev/null 2>&1; then
  say "asking apt for the kernel package (apt-get update)"
  apt-get update -qq >/dev/null 2>&1 || true
  KPKG=$(apt-cache depends linux-image-amd64 2>/dev/null |
         sed -n 's/.*Depends: \(linux-image-[0-9].*-amd64\)$/\1/p' | head -n1)
fi
[ -n "$KPKG" ] || cannot "no kernel cached in $DIR and apt knows no linux-image-amd64 (no Debian archive here?)"

if [ -f vmlinux ] && [ -f initramfs.cpio.gz ] && [ "$CACHED" = "$KPKG" ] &&
   [ "$(cat initramfs-scripts 2>/dev/null)" = "$SCRIPTS_HASH" ]; then
  exit 0
fi
say "preparing $KPKG in $DIR"
if ! ls debs/"$KPKG"_*.deb >/dev/null 2>&1; then
  command -v apt-get >/dev/null 2>&1 || cannot "apt-get not found: cannot download $KPKG"
  (cd debs && apt-get download -q "$KPKG" >/dev/null 2>&1) ||
    (apt-get update -qq >/dev/null 2>&1 && cd debs && apt-get download -q "$KPKG" >/dev/null 2>&1) ||
    cannot "apt-get download $KPKG failed (no access to the Debian archive?)"
fi
rm -rf kroot && mkdir kroot
dpkg-deb -x debs/"$KPKG"_*.deb kroot
# Boot the uncompressed ELF (PVH entry): saves ~3 s of in-guest xz decompression under TCG.
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
# Keep only this kernel's package.
find debs -name '*.deb' ! -name "${KPKG}_*" -delete
echo "$KPKG" > kernel-package
echo "$SCRIPTS_HASH" > initramfs-scripts
say "ready: $DIR/vmlinux, $DIR/initramfs.cpio.gz"
