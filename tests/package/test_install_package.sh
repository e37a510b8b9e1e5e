#!/usr/bin/env bash
# The installed a3rig needs nothing from the tree it was built from: `cmake --install` into a
# temporary prefix lays out the program, its data and the LCM types; `cpack -G DEB` makes the
# a3rig package with Debian runtime Depends; the package's a3rig, unpacked with dpkg-deb -x, flies
# a scenario in virtual time from a folder outside the source tree, under strace, touching no
# file of the source or build tree, and writes an episode that `a3rig validate` accepts and an
# LCM log that the packaged a3rig-read-lcm-log decodes with the packaged Python types.
# Exit 77 (skipped) without strace or dpkg-deb.
# Usage: test_install_package.sh SOURCE_DIR BUILD_DIR SCENARIO
set -euo pipefail
source_dir=$(cd "$1" && pwd) build_dir=$(cd "$2" && pwd) scenario=$3
for tool in strace dpkg-deb dpkg-shlibdeps; do
  command -v "$tool" >/dev/null || { echo "skipped: no $tool (Debian: strace, dpkg-dev)"; exit 77; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
ok() { echo "ok: $*"; }

prefix=$tmp/prefix
cmake --install "$build_dir" --prefix "$prefix" >"$tmp/install.log" || { cat "$tmp/install.log"; fail "cmake --install"; }
for f in bin/a3rig bin/a3rig-lcm-spy bin/a3rig-read-lcm-log share/a3rig/scenarios/$scenario.json \
         share/a3rig/airframes/iris.json share/a3rig/schema/episode.schema.json \
         share/a3rig/schema/scenario.schema.json share/a3rig/slice_profiles.json \
         share/a3rig/fc_params.default.json share/a3rig/lcmtypes/vehicle_state_t.lcm \
         lib/python3/dist-packages/a3lcm/vehicle_state_t.py; do
  [ -f "$prefix/$f" ] || fail "cmake --install did not install $f"
done
ok "cmake --install laid out the program, its data and the Python types under $prefix"

(cd "$tmp" && cpack -G DEB --config "$build_dir/CPackConfig.cmake" -B "$tmp/pkg" >"$tmp/cpack.log" 2>&1) ||
  { cat "$tmp/cpack.log"; fail "cpack -G DEB"; }
deb=$(find "$tmp/pkg" -maxdepth 1 -name 'a3rig_*.deb' | head -n 1)
[ -n "$deb" ] || { cat "$tmp/cpack.log"; fail "cpack made no a3rig_*.deb"; }
depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
for lib in liblcm1 libc6 libstdc++6 libjs-d3; do
  [[ "$depends" == *"$lib"* ]] || fail "the package does not depend on $lib"
done
ok "$(basename "$deb") depends on the Debian runtime libraries and libjs-d3"

root=$tmp/root
dpkg-deb -x "$deb" "$root"
a3rig=$root/usr/bin/a3rig
mkdir "$tmp/work"
cd "$tmp/work"
env -u A3_SHARED_DIR strace -f -qq -e trace=%file -o "$tmp/trace" \
  "$a3rig" run --runtime virtual --scenario "$scenario" --out "$tmp/run" --no-plot --quiet ||
  fail "the packaged a3rig run exited $?"
if grep -F -e "\"$source_dir/" -e "\"$source_dir\"" -e "\"$build_dir/" -e "\"$build_dir\"" "$tmp/trace" >"$tmp/tree_access"; then
  head -n 20 "$tmp/tree_access"
  fail "the packaged a3rig touched $(wc -l <"$tmp/tree_access") paths of the source or build tree"
fi
ok "the packaged a3rig ran from $tmp/work without touching $source_dir or $build_dir"

"$a3rig" validate "$tmp/run/episode.json" || fail "a3rig validate rejected the episode"
ok "the episode it wrote is valid"

# Its α³-Bench corpus is looked for under the package's own share/a3rig, not beside the build tree.
status=0
env -u A3_SHARED_DIR "$a3rig" run --runtime virtual --scenario alphabench:absent/episode.json \
  --out "$tmp/corpus-run" --quiet >"$tmp/corpus.log" 2>&1 || status=$?
grep -q "$root/usr/share/a3rig/shared/alphabench/eval_runs/absent/episode.json" "$tmp/corpus.log" ||
  { cat "$tmp/corpus.log"; fail "the packaged a3rig did not look for the corpus under $root/usr/share/a3rig/shared (exit $status)"; }
ok "the packaged a3rig looks for the corpus under its share/a3rig/shared"

# The packaged LCM log reader finds the packaged Python types.
"$root/usr/bin/a3rig-read-lcm-log" "$tmp/run" >"$tmp/read.log" || { cat "$tmp/read.log"; fail "a3rig-read-lcm-log"; }
if ! grep -q "^messages of no a3lcm type: 0$" "$tmp/read.log" || ! grep -q "^vehicle states: [1-9]" "$tmp/read.log"; then
  cat "$tmp/read.log"
  fail "a3rig-read-lcm-log did not decode the run's log"
fi
ok "the packaged a3rig-read-lcm-log decoded the run's LCM log with the packaged Python types"
