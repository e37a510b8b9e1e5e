#!/bin/sh
# PID 1 of the vcan test VM (runs from the initramfs with static busybox).
# Kernel command line: a3_cmd=<script on the host fs> a3_tag=<nonce> [a3_rw=<host dir>]
# Mounts the host / over 9p read-only with a tmpfs overlay, chroots into it, brings up lo and
# vcan0, runs the script with the host's /bin/sh, prints "A3VM_EXIT_<nonce>=<status>" on the
# serial console and powers off.
export PATH=/bin
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
exec </dev/console >/dev/console 2>&1

for m in $(cat /lib/modules/order); do
  insmod /lib/modules/$m 2>/dev/null || echo "a3vm: insmod $m failed"
done

CMD=; TAG=x; RW=
for a in $(cat /proc/cmdline); do
  case "$a" in
    a3_cmd=*) CMD=${a#a3_cmd=} ;;
    a3_tag=*) TAG=${a#a3_tag=} ;;
    a3_rw=*)  RW=${a#a3_rw=} ;;
  esac
done

rc=99
if mount -t 9p -o trans=virtio,version=9p2000.L,ro,msize=262144,cache=loose hostroot /host; then
  mount -t tmpfs -o size=50% tmpfs /ovl
  mkdir -p /ovl/upper /ovl/work
  if mount -t overlay overlay -o lowerdir=/host,upperdir=/ovl/upper,workdir=/ovl/work /newroot; then
    R=/newroot
  else
    echo "a3vm: overlay failed, using the read-only root with a tmpfs /tmp"
    R=/host; mount -t tmpfs tmpfs $R/tmp; mount -t tmpfs tmpfs $R/root
  fi
  mount -t proc proc $R/proc
  mount -t sysfs sysfs $R/sys
  mount -t devtmpfs devtmpfs $R/dev
  mkdir -p $R/dev/pts $R/dev/shm
  mount -t devpts devpts $R/dev/pts
  mount -t tmpfs tmpfs $R/dev/shm
  mount -t tmpfs tmpfs $R/run
  if [ -n "$RW" ]; then
    mount -t 9p -o trans=virtio,version=9p2000.L,msize=262144 rwdir $R$RW || echo "a3vm: read-write mount failed"
  fi
  chroot $R /usr/bin/env -i HOME=/root TERM=dumb \
      PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
      /bin/sh -c 'ip link set lo up && ip link add dev vcan0 type vcan && ip link set up vcan0 || echo "a3vm: vcan0 setup failed"; exec /bin/sh "$0"' "$CMD"
  rc=$?
  [ -n "$RW" ] && umount $R$RW 2>/dev/null
else
  echo "a3vm: mounting the host root over 9p failed"
fi
echo
echo "A3VM_EXIT_$TAG=$rc"
poweroff -f
