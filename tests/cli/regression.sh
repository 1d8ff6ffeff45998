#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# The default case's observables against stored reference values.
# Refresh (after an intended change of the model): run the default case and
# copy its summary.json to tests/regression/default_summary.json.
set -eu
BIN="$1"; CASES="$2"; HERE="$(cd "$(dirname "$0")" && pwd)"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
"$BIN" -q simulate "$CASES/default.toml" --out "$work/default"
/usr/bin/python3 "$HERE/compare_json.py" "$work/default/summary.json" "$HERE/../regression/default_summary.json" 1e-6 1e-9
# No inverted element in any posture's deformed state.
/usr/bin/python3 -c "
import json, sys
s = json.load(open('$work/default/summary.json'))
bad = [p['posture'] for p in s['postures'] if not p['min_det_F'] > 0]
sys.exit('min det F <= 0 in ' + ', '.join(bad) if bad else 0)"
echo "2 passed, 0 failed"
