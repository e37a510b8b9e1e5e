#!/bin/sh
# Builds the VM's initramfs: static busybox, the virtio/9p/overlay/CAN modules and guest-init.sh
# as /init. Usage: build-initramfs.sh <unpacked linux-image-*-amd64 root> <out.cpio.gz>
set -eu
KROOT=$1
OUT=$2
KVER=$(ls "$KROOT/lib/modules" | head -n1)
MODS="$KROOT/lib/modules/$KVER/kernel"
HERE=$(cd "$(dirname "$0")" && pwd)
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

mkdir -p "$T/bin" "$T/lib/modules" "$T/proc" "$T/sys" "$T/dev" "$T/host" "$T/ovl" "$T/newroot"
cp /bin/busybox "$T/bin/busybox"
for a in sh mount umount insmod mkdir cat echo poweroff chroot; do ln -s busybox "$T/bin/$a"; done

# The .deb ships no modules.dep and insmod resolves nothing: list dependencies first.
for m in \
  drivers/virtio/virtio_ring.ko drivers/virtio/virtio.ko \
  drivers/virtio/virtio_pci_modern_dev.ko drivers/virtio/virtio_pci_legacy_dev.ko \
  drivers/virtio/virtio_pci.ko \
  net/9p/9pnet.ko net/9p/9pnet_virtio.ko fs/netfs/netfs.ko fs/fscache/fscache.ko fs/9p/9p.ko \
  fs/overlayfs/overlay.ko \
  net/can/can.ko net/can/can-raw.ko drivers/net/can/dev/can-dev.ko drivers/net/can/vcan.ko
do
  if [ -f "$MODS/$m" ]; then
    cp "$MODS/$m" "$T/lib/modules/"
    basename "$m" >> "$T/lib/modules/order"
  fi
done

cp "$HERE/guest-init.sh" "$T/init"
chmod +x "$T/init"
(cd "$T" && find . | busybox cpio -o -H newc 2>/dev/null | gzip -1) > "$OUT"
