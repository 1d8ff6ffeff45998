#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Load test of `breastsim serve` (tests/app/load.py) on a free loopback port
# with a scratch --data folder.
set -eu
BIN="$1"; HERE="$(cd "$(dirname "$0")" && pwd)"
work=$(mktemp -d)
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
/usr/bin/python3 "$HERE/load.py" "$port"
kill -0 "$server_pid"   # still running
