#!/usr/bin/env bash
# Installs the npm packages pinned in tests/npm/package.json + package-lock.json (the official
# OpenAI and MCP SDKs) into a cache outside the repository, and prints that folder (the parent
# of its node_modules) as the last line on stdout. Tests then run node with that folder's
# node_modules on NODE_PATH or import from it.
#   Cache: ${A3_NPM_DIR:-$HOME/.cache/a3rig/npm}; reused while the lock file is unchanged
#   (sha256 of package.json + package-lock.json kept in .a3-lock-hash).
#   Exit 0: installed; exit 77 (ctest's skip code): node/npm missing, node < 18, or the npm
#   registry not reachable; any other non-zero: npm ci failed for another reason.
# Safe to call from several tests at once: the install holds a flock on the cache folder.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cache=${A3_NPM_DIR:-$HOME/.cache/a3rig/npm}
how_to_run="to run them, install nodejs >= 18 and npm (scripts/setup.sh) and make registry.npmjs.org reachable, or point A3_NPM_DIR at a folder where tests/npm/install.sh has already run"

skip() {
  echo "install.sh: $1: skipping the SDK tests; $how_to_run" >&2
  exit 77
}

command -v node >/dev/null 2>&1 || skip "node not found"
command -v npm >/dev/null 2>&1 || skip "npm not found"
node_major=$(node -p 'process.versions.node.split(".")[0]')
[ "$node_major" -ge 18 ] || skip "node $(node --version) is older than 18"

mkdir -p "$cache"
exec 9>"$cache/.a3-install.lock"
flock 9

want_hash=$(cat "$here/package.json" "$here/package-lock.json" | sha256sum | cut -d' ' -f1)
have_hash=$(cat "$cache/.a3-lock-hash" 2>/dev/null || true)
if [ "$want_hash" = "$have_hash" ] && [ -d "$cache/node_modules" ]; then
  echo "$cache"
  exit 0
fi

# A quick probe first: npm ci itself retries for a minute or more before giving up.
if ! timeout 20 npm ping --fetch-retries=0 --fetch-timeout=10000 >/dev/null 2>&1; then
  skip "npm registry not reachable ($(npm config get registry 2>/dev/null))"
fi
cp "$here/package.json" "$here/package-lock.json" "$cache/"
rm -f "$cache/.a3-lock-hash"
log="$cache/.a3-npm-ci.log"
if ! (cd "$cache" && npm ci --no-audit --no-fund --loglevel=error) >"$log" 2>&1; then
  if grep -qiE 'ENOTFOUND|ECONNREFUSED|ETIMEDOUT|EAI_AGAIN|ECONNRESET|network|E404|ENETUNREACH' "$log"; then
    tail -n 5 "$log" >&2
    skip "npm registry not reachable"
  fi
  echo "install.sh: npm ci failed in $cache (log: $log):" >&2
  tail -n 20 "$log" >&2
  exit 1
fi
echo "$want_hash" >"$cache/.a3-lock-hash"
echo "$cache"
