#!/usr/bin/env bash
# Runs one node:test file of tests/npm against the pinned SDKs: installs them with install.sh
# (exit 77, ctest's skip code, when npm cannot be used), then `node --test FILE` with
# A3_NPM_DIR set. Usage: run_node_test.sh FILE.test.mjs  (environment: A3RIG = the a3rig program)
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=$("$here/install.sh")
rc=$?
[ "$rc" = 0 ] || exit "$rc"
A3_NPM_DIR=$(printf '%s\n' "$out" | tail -n 1)
export A3_NPM_DIR
exec node --test "$1"
