#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# The default-case surgery started from the planning app (the job the page
# posts) against `breastsim surgery cases/default.toml`, alternating, in the
# same run: medians of REPEATS and their ratio (target: app <= 1.10 x CLI).
# Usage: bash bench/app_surgery.sh [BUILD_DIR=build] [REPEATS=3]
set -eu
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${1:-$ROOT/build}"; REPEATS="${2:-3}"
work=$(mktemp -d)
"$BUILD/breastsim" serve --port 0 --data "$work/data" > "$work/serve.out" 2>&1 &
server_pid=$!
trap 'kill "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true; rm -rf "$work"' EXIT
port=""
for _ in $(seq 1 100); do
  port=$(grep -o 'listening on http://127.0.0.1:[0-9]*' "$work/serve.out" 2>/dev/null | grep -o '[0-9]*$' || true)
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || { cat "$work/serve.out"; exit 1; }
python3 "$ROOT/bench/app_surgery.py" "$BUILD/breastsim" "$ROOT/cases/default.toml" "$port" "$work" "$REPEATS"
