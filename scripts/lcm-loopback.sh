#!/usr/bin/env bash
# Lets LCM's UDP multicast (udpm://239.255.76.67:7667, ttl=0) work on this host alone: turns on
# multicast on the loopback interface and routes LCM's group there (root only; idempotent).
# Without it LCM fails with "Couldn't create LCM" or delivers nothing (lcm-proj #60, #476, #579).
set -u
group=${1:-239.255.76.67}
if ! command -v ip >/dev/null 2>&1; then
  echo "lcm-loopback: 'ip' not found (apt-get install iproute2)" >&2
  exit 1
fi
ip link set lo multicast on || { echo "lcm-loopback: cannot enable multicast on lo (root needed)" >&2; exit 1; }
if ! ip route show "$group/32" dev lo 2>/dev/null | grep -q .; then
  ip route add "$group/32" dev lo || { echo "lcm-loopback: cannot add the route for $group on lo" >&2; exit 1; }
fi
echo "lcm-loopback: multicast on lo, route $group/32 dev lo"
