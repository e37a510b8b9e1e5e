#!/usr/bin/env bash
# Starts lcm-spy, or lcm-logplayer-gui, on Debian's Java with a3rig's LCM types jar on the class
# path, so that they decode the rig's messages. Debian 12's /usr/bin/lcm-spy and
# /usr/bin/lcm-logplayer-gui pass -Xincgc, which OpenJDK 17 refuses ("Unrecognized option:
# -Xincgc"); this starts the same classes without it.
# Usage: lcm-spy.sh [--logplayer] [ARGS...]   (ARGS go to lcm-spy or lcm-logplayer-gui)
#   lcm-spy.sh --lcm-url 'udpm://239.255.76.67:PORT?ttl=0'   watch a live run (a3rig run prints its URL)
#   lcm-spy.sh --lcm-url 'file:///abs/out/run/episode.lcmlog?speed=1'   read a log straight into lcm-spy
#   lcm-spy.sh --logplayer --lcm-url URL out/run/episode.lcmlog   replay a log onto URL (lcm-spy on URL watches)
# The types jar: $A3_LCM_TYPES_JAR, else <prefix>/share/java/a3lcm-types.jar beside an installed
# copy of this script (<prefix>/bin), else build/lcmtypes/a3lcm-types.jar of this repository.
# Needs Debian's default-jre (or default-jdk-headless plus a display), liblcm-java and
# libjchart2d-java (lcm-spy's charts).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
java_dir=/usr/share/java

fail() { echo "lcm-spy.sh: $*" >&2; exit 1; }

types_jar() {
  local candidate
  for candidate in "${A3_LCM_TYPES_JAR:-}" "$here/../share/java/a3lcm-types.jar" "$here/../build/lcmtypes/a3lcm-types.jar"; do
    if [ -n "$candidate" ] && [ -f "$candidate" ]; then echo "$candidate"; return; fi
  done
  fail "no a3lcm-types.jar (set A3_LCM_TYPES_JAR, or build a3rig with javac and liblcm-java installed)"
}

main_class=lcm.spy.Spy
if [ "${1:-}" = --logplayer ]; then
  main_class=lcm.logging.LogPlayer
  shift
fi
command -v java >/dev/null || fail "no java (Debian: apt-get install default-jre)"
[ -f "$java_dir/lcm.jar" ] || fail "no $java_dir/lcm.jar (Debian: apt-get install liblcm-java)"
class_path="$java_dir/lcm.jar:$(types_jar)"
if [ "$main_class" = lcm.spy.Spy ]; then
  [ -f "$java_dir/jchart2d.jar" ] || fail "no $java_dir/jchart2d.jar (Debian: apt-get install libjchart2d-java)"
  class_path="$class_path:$java_dir/jchart2d.jar"
fi
exec java -Djava.net.preferIPv4Stack=true -Xmx256m -ea -cp "$class_path" "$main_class" "$@"
