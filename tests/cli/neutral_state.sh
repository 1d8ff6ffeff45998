#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# `breastsim neutral-state`: the cap taken as a shape recorded standing; its
# stress-free reference, simulated standing, must reproduce the cap (nipple,
# lowest point, projection within 1e-6 m), and so must the reference plus the
# displacement written for ParaView; bad options leave no output.
# Usage: neutral_state.sh BREASTSIM CASES_DIR
set -eu
BIN="$1"; CASES="$2"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$BIN" -q neutral-state "$CASES/default.toml" --set geometry.mesh_size=0.012 --posture standing \
  --set output.vtk=true --out neutral >neutral.log
for f in reference.msh case.reference.toml summary.json neutral_standing.xdmf neutral_standing.h5 \
  neutral_standing.pvd; do
  [ -s "neutral/$f" ] || { echo "FAIL: neutral/$f missing"; exit 1; }
done
"$BIN" -q simulate neutral/case.reference.toml --set postures.names=standing --out forward >forward.log
python3 - <<'PY'
import json, sys
ns = json.load(open("neutral/summary.json"))
p = json.load(open("forward/summary.json"))["postures"][0]
n, zmin, proj = p["nipple_m"], p["z_min_m"], p["projection_m"]
err = max(abs(n[0]), abs(n[1] - 0.06), abs(n[2]), abs(zmin + 0.07), abs(proj - 0.06))
print(f"neutral state: {len(ns['iterations'])} iterations, {ns['wall_time_s']:.2f} s, node shift "
      f"{1e3 * ns['max_node_shift_m']:.2f} mm; forward from it: nipple {[round(1e3 * v, 4) for v in n]} mm, "
      f"largest error {err:.2e} m")
if not ns["converged"] or ns["max_node_shift_m"] < 0.01 or err > 1e-6:
    sys.exit("FAIL: the reference does not reproduce the recorded shape")
# The fields file: reference points X and displacement u; X + u is the cap.
import glob, xml.etree.ElementTree as ET
x = []
for f in glob.glob("neutral/neutral_standing_p*.vtu"):
    root = ET.parse(f).getroot()
    X = [float(v) for v in root.find(".//Points/DataArray").text.split()]
    u = next([float(v) for v in a.text.split()] for a in root.iter("DataArray")
             if a.get("Name") == "displacement")
    x += [[X[3 * i + k] + u[3 * i + k] for k in range(3)] for i in range(len(X) // 3)]
top, low = max(p[1] for p in x), min(p[2] for p in x)
print(f"neutral_standing fields: X + u projection {1e3 * top:.4f} mm, lowest {1e3 * low:.4f} mm")
if abs(top - 0.06) > 1e-6 or abs(low + 0.07) > 1e-6:
    sys.exit("FAIL: reference + displacement in the fields file is not the recorded cap")
PY
refuse() { # NAME MESSAGE ARGS...: exit 2, the message, no output folder
  local name="$1" msg="$2"; shift 2
  if "$BIN" -q neutral-state "$CASES/default.toml" "$@" --out "bad_$name" >"$name.log" 2>&1; then
    echo "FAIL: $name accepted"; exit 1; fi
  grep -q -- "$msg" "$name.log" || { echo "FAIL: $name: no '$msg' in:"; cat "$name.log"; exit 1; }
  [ ! -e "bad_$name" ] || { echo "FAIL: $name left output"; exit 1; }
}
refuse tolerance "--tolerance = 1 is out of range" --tolerance 1
refuse theta "--theta = 200 is out of range" --theta 200
refuse iterations "--max-iterations = 0 is out of range" --max-iterations 0
refuse nipple "'geometry.nipple_z' = 0.01 needs geometry.mesh_file" --set geometry.nipple_z=0.01
echo "neutral_state: ok"
