#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# `calibrate` and `diagnose` with --ranks-per-case 1 on 2 ranks give the
# serial results. calibrate solves its finite-difference Jacobian's columns
# side by side: the same fitted values and standard errors to 1e-6 relative
# (each group's solves start from its own warm starts, so the solutions
# differ within the Newton tolerance). diagnose solves the postures of every
# evaluation side by side, each posture always on the same group from its
# own warm start as in serial: the same discoveries and the fitted values to
# 1e-9 in ln p (measured: identical). A K that does not divide the ranks is
# refused with exit code 2 and no output.
# Usage: calibrate_groups.sh BREASTSIM CASES_DIR
set -eu
BIN="$1"; CASES="$2"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

# Calibrate mu and c (two Jacobian columns) on a coarse mesh.
printf '[geometry]\nmesh_size = 0.016\n[tissue]\nmu = 300.0\n' > "$work/start.toml"
printf '[geometry]\nmesh_size = 0.016\n' > "$work/truth.toml"
"$BIN" -q measure "$work/truth.toml" --mesh-size 0.012 --noise 0.0005 --seed 3 --out "$work/m.json"
cal=(calibrate "$work/m.json" --case "$work/start.toml" --fit mu,c --algorithm lbfgs
     --max-evals 30 --size 320x240)
"$BIN" -q "${cal[@]}" --out "$work/cal_serial" > /dev/null
mpirun -n 2 "$BIN" -q "${cal[@]}" --ranks-per-case 1 --out "$work/cal_groups" > /dev/null

# Diagnose a hidden base-spring effect on a coarse mesh (fits, probes, refits, checks).
sets=(--set geometry.mesh_size=0.014 --set base.fixed=true --set terms.base_springs=false)
"$BIN" -q record "$CASES/default.toml" "${sets[@]}" --hidden base_springs --seed 7 \
  --mesh-size 0.008 --out "$work/rec.json"
dia=(diagnose "$work/rec.json" --case "$CASES/default.toml" "${sets[@]}")
"$BIN" -q "${dia[@]}" --out "$work/dia_serial" > /dev/null
mpirun -n 2 "$BIN" -q "${dia[@]}" --ranks-per-case 1 --out "$work/dia_groups" > /dev/null

/usr/bin/python3 - "$work" <<'PY'
import json, math, sys
from pathlib import Path
w = Path(sys.argv[1])
load = lambda p: json.loads((w / p).read_text())
def rel(a, b):
    return abs(a - b) / max(abs(a), 1e-30)
worst = 0.0
a, b = load("cal_serial/report.json"), load("cal_groups/report.json")
assert b["rank_groups"] == 2, b.get("rank_groups")
for pa, pb in zip(a["fit"], b["fit"]):
    assert pa["name"] == pb["name"]
    worst = max(worst, rel(pa["fitted"], pb["fitted"]), rel(pa["standard_error"], pb["standard_error"]))
print(f"calibrate mu,c on 2 ranks x 1 = serial: largest relative difference {worst:.2e}")
assert worst <= 1e-6, worst
a, b = load("dia_serial/diagnosis.json"), load("dia_groups/diagnosis.json")
assert a["discovered"] == b["discovered"] == ["base_springs"], (a["discovered"], b["discovered"])
worst = 0.0
for pa, pb in zip(a["final"]["parameters"], b["final"]["parameters"]):
    assert pa["name"] == pb["name"]
    worst = max(worst, abs(math.log(pa["value"] / pb["value"])))
print(f"diagnose on 2 ranks x 1 = serial: {b['discovered']}, largest difference in ln p {worst:.2e}")
assert worst <= 1e-9, worst
PY

if mpirun -n 2 "$BIN" -q "${cal[@]}" --ranks-per-case 3 --out "$work/bad" > "$work/bad.log" 2>&1; then
  echo "FAIL: --ranks-per-case 3 on 2 ranks accepted"; exit 1; fi
grep -q "ranks-per-case = 3 is out of range" "$work/bad.log" || { cat "$work/bad.log"; exit 1; }
[ ! -e "$work/bad" ] || { echo "FAIL: refused calibrate left output"; exit 1; }
echo "calibrate_groups: ok"
