#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Surgery on the real shape (docs/SCANS.md "Surgery on a full breast"): a
# full, asymmetric synthetic patient goes scan -> scan-model -> neutral-state
# -> surgery, serially and on 2 MPI ranks; every suture closes to < 0.1 mm
# (the keel faces sewn to each other by the mirror map, P2 to the chest), the
# two runs resect the same volume, kept + resected = the neutral breast
# within 2 %; impossible plans and a half model's mesh are refused with exit
# code 2, a message naming the key and no output.
# Usage: full_breast_surgery.sh BREASTSIM
set -eu -o pipefail
BIN="$1"; PY=/usr/bin/python3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$BIN" -q synthetic-patient --volume 400 --ptosis 0.3 --lateral 0.1 --asymmetry 0.3 --mesh-size 0.01 \
  --format stl --out patient >/dev/null
"$BIN" -q scan-model patient/scan.stl --units mm --posture standing --chest patient/chest.stl --mesh-size 0.01 \
  --out model >/dev/null
"$BIN" -q neutral-state model/case.toml --posture standing --out neutral >/dev/null
set=(--set postures.names=standing,supine --set output.xdmf=false)
"$BIN" -q surgery neutral/case.reference.toml "${set[@]}" --out serial >serial.log
mpirun -n 2 "$BIN" -q surgery neutral/case.reference.toml "${set[@]}" --out ranks2 >ranks2.log
$PY - serial/summary.json ranks2/summary.json <<'PY'
import json, sys
s, m = (json.load(open(f)) for f in sys.argv[1:3])
for name, r in (("serial", s), ("2 ranks", m)):
    g = r["suture"]
    print("%s: keel gap %.4f mm, chest gap %.4f mm, resected %.2f cm3 (mesh %.2f) of %.2f cm3, face A %s"
          % (name, 1e3 * g["max_gap_keel_m"], 1e3 * g["max_gap_chest_m"], 1e6 * r["resected_volume_m3"],
             1e6 * r["resected_volume_mesh_m3"], 1e6 * r["volume_pre_m3"], g["face_a"]))
    if r["model"] != "full breast" or len(r["postop"]) != 2:
        sys.exit("FAIL: %s: not a full-breast surgery with two post-op postures" % name)
    if not (g["max_gap_keel_m"] < 1e-4 and g["max_gap_chest_m"] < 1e-4 and g["max_gap_m"] < 1e-4):
        sys.exit("FAIL: %s: a suture gap is not below 0.1 mm: %s" % (name, g))
    kept_plus_cut = r["volume_remaining_m3"] + r["resected_volume_mesh_m3"]
    if abs(kept_plus_cut / r["volume_pre_m3"] - 1) > 0.02 or r["resected_volume_m3"] <= 0:
        sys.exit("FAIL: %s: kept + resected = %g m3 against the neutral %g m3" % (name, kept_plus_cut, r["volume_pre_m3"]))
    D, Dm = r["incision"]["D_m"], r["incision"]["D_mirror_m"]
    if not (D[0] > 0 > Dm[0] and abs(D[1] - Dm[1]) < 1e-9):
        sys.exit("FAIL: %s: D = %s and D' = %s are not on P1 and P1' at y = h" % (name, D, Dm))
if abs(s["resected_volume_m3"] / m["resected_volume_m3"] - 1) > 1e-9:
    sys.exit("FAIL: resected %r m3 serially, %r m3 on 2 ranks" % (s["resected_volume_m3"], m["resected_volume_m3"]))
for a, b in zip(s["postop"], m["postop"]):
    if max(abs(x - y) for x, y in zip(a["nipple_m"], b["nipple_m"])) > 1e-6:
        sys.exit("FAIL: post-op nipple %s serially, %s on 2 ranks" % (a["nipple_m"], b["nipple_m"]))
PY

refuse() { # NAME MESSAGE CASE ARGS...: exit 2, the message, no output folder
  local name="$1" msg="$2" case="$3"; shift 3
  set +e; "$BIN" -q surgery "$case" "$@" --out "bad_$name" >"$name.log" 2>&1; code=$?; set -e
  [ "$code" = 2 ] || { echo "FAIL: $name: exit $code, not 2"; cat "$name.log"; exit 1; }
  grep -qF -- "$msg" "$name.log" || { echo "FAIL: $name: no '$msg' in:"; cat "$name.log"; exit 1; }
  [ ! -e "bad_$name" ] || { echo "FAIL: $name left output"; exit 1; }
  ls -d bad_"$name".partial-* >/dev/null 2>&1 && { echo "FAIL: $name left a staging folder"; exit 1; }
  echo "ok   $name: $(head -c 160 "$name.log")"
}
ref=neutral/case.reference.toml
refuse s_above_rim "key 'incision.s' = 0.2" $ref --set incision.s=0.2
refuse h_above_A "key 'incision.h' = 0.09" $ref --set incision.h=0.09
refuse d_below_rim "key 'incision.d' = 0.3" $ref --set incision.d=0.3
refuse b_outside "key 'incision.a_deg' = 75" $ref --set incision.a_deg=75
"$BIN" -q scan-model patient/scan.stl --units mm --posture standing --chest patient/chest.stl --mesh-size 0.012 \
  --half --out half >/dev/null
refuse half_model "is a half model" half/case.toml
mpirun -n 2 "$BIN" -q surgery $ref --set incision.s=0.2 --out bad_mpi >mpi.log 2>&1 && { echo "FAIL: 2 ranks accepted s = 0.2"; exit 1; }
grep -qF "key 'incision.s' = 0.2" mpi.log && [ ! -e bad_mpi ] || { echo "FAIL: 2-rank refusal"; cat mpi.log; exit 1; }
echo "full breast surgery: passed"
