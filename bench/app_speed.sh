#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# The planning app's surgery job and a 3 x 3 sweep job, served by a baseline
# binary (OLD, e.g. one built from an earlier commit) and by this one (NEW),
# posted alternately in the same run: medians of REPEATS and the ratios
# old / new; both must resect the same volumes (bench/app_speed.py).
# Usage: bash bench/app_speed.sh OLD NEW [REPEATS=3]
set -eu
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
OLD="$(readlink -f "$1")"; NEW="$(readlink -f "$2")"; REPEATS="${3:-3}"
work=$(mktemp -d)
pids=()
trap 'for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; wait "$p" 2>/dev/null || true; done; rm -rf "$work"' EXIT
serve() { # BINARY NAME -> prints the port
  "$1" serve --port 0 --data "$work/data-$2" > "$work/serve-$2.out" 2>&1 &
  pids+=($!)
  for _ in $(seq 1 100); do
    port=$(grep -o 'listening on http://127.0.0.1:[0-9]*' "$work/serve-$2.out" 2>/dev/null | grep -o '[0-9]*$' || true)
    [ -n "$port" ] && return 0
    sleep 0.1
  done
  cat "$work/serve-$2.out" >&2; exit 1
}
serve "$OLD" old; old_port=$port
serve "$NEW" new; new_port=$port
PYTHONPATH="$ROOT/bench" python3 "$ROOT/bench/app_speed.py" "$old_port" "$new_port" "$REPEATS"
