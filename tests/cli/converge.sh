#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# `breastsim converge` end to end on a tiny case (coarse cap, 3 levels of
# geometry.refinements, P1): convergence.json has one study with the three
# levels, growing cell counts, the requested quantities with finite values,
# orders, Richardson value and GCI; the nipple drop increases in magnitude
# with refinement (a coarse mesh is too stiff) and the Richardson value lies
# beyond the finest level; convergence.txt and a non-empty PNG are written.
# --refine red gives the same level 0 and cell counts. Bad input: --levels 1,
# an unknown quantity, a surgery quantity without --stage surgery, and
# --refine red with it, the incompressible MMS's --mms-kappa without the
# mixed formulation and --mms-length 0 are rejected with a message naming the
# option and no output folder.
set -eu
BIN="$1"; CASES="$2"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
"$BIN" -q converge "$CASES/default.toml" --levels 3 --quantity nipple_z,energy \
  --set geometry.mesh_size=0.03 --out "$work/conv"
test -s "$work/conv/convergence.txt"
test -s "$work/conv/convergence.png"
/usr/bin/python3 - "$work/conv/convergence.json" <<'PY'
import json, math, sys
d = json.load(open(sys.argv[1]))
assert d["levels"] == 3 and d["stage"] == "preop", d
s, = d["studies"]
assert s["refinements"] == [0, 1, 2], s["refinements"]
c = s["cells"]
assert c[1] == 8 * c[0] and c[2] == 8 * c[1], c     # uniform splitting
z = s["quantities"]["nipple_z"]
checks = [
    set(s["quantities"]) == {"nipple_z", "energy"},
    all(math.isfinite(v) for q in s["quantities"].values() for v in q["values"]),
    z["values"][0] < 0 and z["values"][2] < z["values"][1] < z["values"][0],  # sags more when finer
    z["monotone"] and z["valid"] and 0 < z["observed_order"] < 4,
    z["richardson"] < z["values"][2],                   # extrapolated beyond the finest level
    0 < z["gci_finest"] < 1,
    len(z["orders"]) == 1 and abs(z["orders"][0] - z["observed_order"]) < 1e-12,
]
print("checks:", checks)
sys.exit(0 if all(checks) else 1)
PY
# Red refinement (--refine red): the same level-0 mesh, hence the same
# level-0 values; 8x cells per level, monotone nipple drop.
"$BIN" -q converge "$CASES/default.toml" --levels 3 --quantity nipple_z,volume --refine red \
  --set geometry.mesh_size=0.03 --out "$work/red"
/usr/bin/python3 - "$work/conv/convergence.json" "$work/red/convergence.json" <<'PY'
import json, sys
g, = json.load(open(sys.argv[1]))["studies"]
r, = json.load(open(sys.argv[2]))["studies"]
zg, zr = g["quantities"]["nipple_z"]["values"], r["quantities"]["nipple_z"]["values"]
checks = [
    g["refinement"] == "gmsh" and r["refinement"] == "red",
    r["cells"] == g["cells"],
    abs(zr[0] - zg[0]) <= 1e-12 * abs(zg[0]),
    zr[2] < zr[1] < zr[0],
]
print("red refinement checks:", checks)
sys.exit(0 if all(checks) else 1)
PY
# Bad input.
set +e
out=$("$BIN" -q converge "$CASES/default.toml" --levels 1 --out "$work/bad" 2>&1); rc=$?
set -e
echo "$out"
[ "$rc" -ne 0 ] && echo "$out" | grep -q -- "--levels" && [ ! -e "$work/bad" ]
set +e
out=$("$BIN" -q converge "$CASES/default.toml" --quantity nipple_q --out "$work/bad" 2>&1); rc=$?
set -e
echo "$out"
[ "$rc" -eq 2 ] && echo "$out" | grep -q "unknown quantity 'nipple_q'" && [ ! -e "$work/bad" ]
set +e
out=$("$BIN" -q converge "$CASES/default.toml" --quantity max_gap --out "$work/bad" 2>&1); rc=$?
set -e
echo "$out"
[ "$rc" -eq 2 ] && echo "$out" | grep -q "needs --stage surgery" && [ ! -e "$work/bad" ]
set +e
out=$("$BIN" -q converge "$CASES/default.toml" --stage surgery --refine red --out "$work/bad" 2>&1); rc=$?
set -e
echo "$out"
[ "$rc" -eq 2 ] && echo "$out" | grep -q -- "--refine red: only with --stage preop" && [ ! -e "$work/bad" ]
set +e
out=$("$BIN" -q converge "$CASES/default.toml" --mms --mms-kappa 2 --out "$work/bad" 2>&1); rc=$?
set -e
echo "$out"
[ "$rc" -eq 2 ] && echo "$out" | grep -q -- '--mms-kappa = 2: only with --mms and tissue.formulation = "mixed"' && [ ! -e "$work/bad" ]
set +e
out=$("$BIN" -q converge "$CASES/default.toml" --mms --mms-length 0 --out "$work/bad" 2>&1); rc=$?
set -e
echo "$out"
[ "$rc" -eq 2 ] && echo "$out" | grep -q -- "--mms-length" && [ ! -e "$work/bad" ]
echo "all converge checks passed"
