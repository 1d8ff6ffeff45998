#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# tissue.formulation = mixed (Taylor-Hood P2-P1) through `simulate` (~15 s):
# the half cap at lambda / mu = 1e3 (P2, 12 mm) solves standing with the
# default skin, springs and gravity, det F > 0, the summary names the
# formulation, and its nipple sags more than the locked P1 displacement
# solution; at lambda / mu = 1e4 the deformed volume stays the cap's to 1e-3; the refusals at the edge (exit code 2, the key named, no output):
# lambda < mu, P1, surgery.
set -u
BIN="$1"; CASES="$2"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
common=(--set geometry.mesh_size=0.012 --set tissue.lambda=400000 --set postures.names=standing)
"$BIN" -q simulate "$CASES/default.toml" "${common[@]}" --set geometry.order=2 \
  --set tissue.formulation=mixed --out "$work/mixed" || fail "mixed simulate"
"$BIN" -q simulate "$CASES/default.toml" "${common[@]}" --set geometry.order=1 --out "$work/p1" \
  || fail "P1 simulate"
# lambda / mu = 1e4 (nu = 0.49995): the deformed volume stays the cap's.
"$BIN" -q simulate "$CASES/default.toml" "${common[@]}" --set geometry.order=2 \
  --set tissue.formulation=mixed --set tissue.lambda=4000000 --out "$work/mixed1e4" || fail "mixed 1e4"
/usr/bin/python3 - "$work/mixed/summary.json" "$work/p1/summary.json" "$work/mixed1e4/summary.json" <<'PY' || exit 1
import json, math, sys
m, p1, m4 = (json.load(open(f)) for f in sys.argv[1:4])
cap = math.pi * 0.06 * (3 * 0.07 ** 2 + 0.06 ** 2) / 6  # full breast, R 70 mm, H 60 mm
v4 = m4["postures"][0]["volume_m3"]
print("lambda/mu 1e4: deformed volume", v4, "cap", cap, "relative change", v4 / cap - 1)
pm, pp = m["postures"][0], p1["postures"][0]
zm, zp = pm["nipple_m"][2], pp["nipple_m"][2]
print("mixed nipple_z", zm, "P1 nipple_z", zp, "min det F", pm["min_det_F"])
print("mixed mean pressure [Pa]", pm["mean_pressure_Pa"])
checks = [m["tissue_formulation"] == "mixed", pm["min_det_F"] > 0, zm < zp - 1e-3,
          abs(pm["mean_pressure_Pa"]) < 1e4, "mean_pressure_Pa" not in pp, abs(v4 / cap - 1) < 1e-3]
print("checks:", checks)
sys.exit(0 if all(checks) else 1)
PY
refused() { # expected key, then arguments
  key="$1"; shift
  out=$("$BIN" -q "$@" 2>&1); rc=$?
  [ $rc -eq 2 ] || fail "exit $rc (expected 2) for: $*"
  echo "$out" | grep -q "$key" || fail "message does not name $key: $out"
}
refused "tissue.lambda" simulate "$CASES/default.toml" --set geometry.order=2 \
  --set tissue.formulation=mixed --set tissue.lambda=0 --out "$work/r1"
refused "tissue.formulation" simulate "$CASES/default.toml" --set tissue.formulation=mixed --out "$work/r2"
refused "tissue.formulation" surgery "$CASES/default.toml" "${common[@]}" --set geometry.order=2 \
  --set tissue.formulation=mixed --out "$work/r3"
for d in r1 r2 r3; do [ ! -e "$work/$d" ] || fail "output written for a refused run ($d)"; done
echo "mixed formulation: ok"
