#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Long study (label long): the apex (nipple) u_z of the default case standing
# at lambda / mu = 1e3 under red refinement of the 30 mm cap (3 levels), with
# tissue.formulation = mixed (P2-P1) and with the P1 displacement formulation.
# Asserted: the mixed values converge monotonically (the increments keep
# their sign and shrink); the P1 values sag less than the mixed finest level
# on every level (locking).
set -eu
BIN="$1"; CASES="$2"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
common=(--levels 3 --quantity nipple_z --refine red --set geometry.mesh_size=0.03 --set tissue.lambda=400000)
"$BIN" -q converge "$CASES/default.toml" "${common[@]}" --order 2 --set geometry.order=2 \
  --set tissue.formulation=mixed --out "$work/mixed"
"$BIN" -q converge "$CASES/default.toml" "${common[@]}" --order 1 --out "$work/p1"
/usr/bin/python3 - "$work/mixed/convergence.json" "$work/p1/convergence.json" <<'PY'
import json, sys
(m,), (p,) = (json.load(open(f))["studies"] for f in sys.argv[1:3])
zm, zp = m["quantities"]["nipple_z"]["values"], p["quantities"]["nipple_z"]["values"]
print("mixed nipple_z", zm, "cells", m["cells"], "unknowns", m["dofs"])
print("P1    nipple_z", zp, "cells", p["cells"], "unknowns", p["dofs"])
d = [zm[i + 1] - zm[i] for i in range(len(zm) - 1)]
checks = [d[0] * d[1] > 0, abs(d[1]) < abs(d[0]), all(z > zm[-1] for z in zp)]
print("checks:", checks)
sys.exit(0 if all(checks) else 1)
PY
