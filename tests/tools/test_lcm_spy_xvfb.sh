#!/usr/bin/env bash
# scripts/lcm-spy.sh starts lcm-spy and lcm-logplayer-gui on Debian 12's OpenJDK (no -Xincgc)
# headless under Xvfb, on a run's episode.lcmlog: lcm-spy reads the log through LCM's file://
# provider and reports the a3lcm types it found on its class path; lcm-logplayer-gui opens the
# log and replays it onto an in-process memq:// bus (no network). Each must still be running
# after 20 and 15 s (generous, for a loaded machine: stopped by timeout, exit 124). Exit 77
# (skipped) without xvfb-run or java.
# Usage: test_lcm_spy_xvfb.sh LCM_SPY_SH TYPES_JAR N_TYPES RUN_DIR
set -euo pipefail
spy=$1 jar=$2 n_types=$3 run_dir=$4
log=$(cd "$run_dir" && pwd)/episode.lcmlog
for tool in xvfb-run java; do
  command -v "$tool" >/dev/null || { echo "skipped: no $tool (Debian: xvfb, default-jdk-headless)"; exit 77; }
done
[ -f "$jar" ] || { echo "skipped: no types jar $jar (the build makes it with javac and liblcm-java)"; exit 77; }
export A3_LCM_TYPES_JAR=$jar
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# run NAME SECONDS ARGS...: lcm-spy.sh ARGS under Xvfb for SECONDS; fails unless still running then.
run() {
  local name=$1 seconds=$2 status=0
  shift 2
  xvfb-run -a timeout "$seconds" "$spy" "$@" >"$out/$name" 2>&1 || status=$?
  cat "$out/$name"
  if [ "$status" != 124 ]; then
    echo "FAIL: $name exited $status within $seconds s (expected to be still running)"
    exit 1
  fi
  if grep -E "Unrecognized option|Could not create the Java Virtual Machine|NoClassDefFoundError" "$out/$name"; then
    echo "FAIL: $name: Java did not start cleanly"
    exit 1
  fi
}

run lcm-spy 20 --lcm-url "file://$log?speed=1"
grep -qx "Found $n_types LCM types" "$out/lcm-spy" || { echo "FAIL: lcm-spy did not find the $n_types a3lcm types"; exit 1; }
echo "ok: lcm-spy found the $n_types a3lcm types and ran"

run lcm-logplayer-gui 15 --logplayer --lcm-url memq:// "$log"
grep -q "^Total seconds: [1-9]" "$out/lcm-logplayer-gui" || { echo "FAIL: lcm-logplayer-gui did not read the log"; exit 1; }
echo "ok: lcm-logplayer-gui opened the log and ran"
