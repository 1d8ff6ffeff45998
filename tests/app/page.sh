#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# The planning app's page in headless Chromium (page_test.js) against
# `breastsim serve` on a free loopback port with a scratch --data folder.
# Usage: [PAGE_SCRIPT=consult_test.js] page.sh BREASTSIM CASES_DIR NODE_MODULES_DIR [SHOT_DIR]
set -eu
BIN="$1"; CASES="$2"; MODULES="$3"; HERE="$(cd "$(dirname "$0")" && pwd)"
[ -x /usr/bin/chromium ] || { echo "Debian's chromium is missing: run bash .ci/setup"; exit 1; }
[ -d "$MODULES/playwright-core" ] || { echo "playwright-core missing in $MODULES: run bash .ci/setup"; exit 1; }
work=$(mktemp -d)
shots="${4:-$work/shots}"; mkdir -p "$shots"
"$BIN" serve --port 0 --data "$work/data" > "$work/serve.out" 2>&1 &
server_pid=$!
trap 'kill "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true; rm -rf "$work"' EXIT
port=""
for _ in $(seq 1 100); do
  port=$(grep -o 'listening on http://127.0.0.1:[0-9]*' "$work/serve.out" 2>/dev/null | grep -o '[0-9]*$' || true)
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || { cat "$work/serve.out"; exit 1; }
NODE_PATH="$MODULES" node "$HERE/${PAGE_SCRIPT:-page_test.js}" "http://127.0.0.1:$port/" "$CASES/measurements_example.json" "$shots" "$BIN"
echo "screenshots: $shots"
