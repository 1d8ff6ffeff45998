#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# `breastsim sweep --ranks-per-case 1` on 2 ranks (each rank one surgery of
# the grid, MPI sub-communicators) gives the serial sweep's table to 1e-10;
# a K that does not divide the ranks is refused with no output.
# Usage: sweep_groups.sh BREASTSIM CASES_DIR
set -eu
BIN="$1"; CASES="$2"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
args=(sweep "$CASES/default.toml" --vary a=25,35 --set postures.names=standing
      --set geometry.mesh_size=0.014 --set solver.coarse_start=false)
"$BIN" -q "${args[@]}" --out "$work/serial"
mpirun -n 2 "$BIN" -q "${args[@]}" --ranks-per-case 1 --out "$work/groups"
/usr/bin/python3 - "$work/serial/sweep.json" "$work/groups/sweep.json" <<'PY'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
assert len(a) == len(b) == 2, (len(a), len(b))
worst = 0.0
for ra, rb in zip(a, b):
    assert ra["parameters"] == rb["parameters"] and ra["ok"] and rb["ok"], (ra, rb)
    for k, v in ra.items():
        if k in ("wall_time_s", "parameters", "ok"):
            continue
        for x, y in zip(v if isinstance(v, list) else [v], rb[k] if isinstance(v, list) else [rb[k]]):
            worst = max(worst, abs(x - y) / max(abs(x), 1e-30))
print(f"sweep on 2 ranks x 1 rank per case = serial: largest relative difference {worst:.2e}")
sys.exit(0 if worst <= 1e-10 else 1)
PY
n=0; for d in "$work"/groups/*=*/; do test -s "$d/summary.json"; n=$((n + 1)); done; [ "$n" = 2 ] || { echo "FAIL: $n surgery folders"; exit 1; }
if mpirun -n 2 "$BIN" -q "${args[@]}" --ranks-per-case 3 --out "$work/bad" >"$work/bad.log" 2>&1; then
  echo "FAIL: --ranks-per-case 3 on 2 ranks accepted"; exit 1; fi
grep -q "ranks-per-case = 3 is out of range" "$work/bad.log" || { cat "$work/bad.log"; exit 1; }
[ ! -e "$work/bad" ] || { echo "FAIL: refused sweep left output"; exit 1; }
echo "sweep_groups: ok"
