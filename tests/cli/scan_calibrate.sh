#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# `breastsim scan-calibrate` (docs/SCANS.md, "Calibration with scans"): a
# synthetic patient (400 cm3, ptosis, lateral turn, asymmetry; tissue.mu =
# 600 Pa) scanned standing, supine and on all fours (holes, 0.5 mm noise) on
# a coarse 10 mm mesh. From standing + supine, starting at the default mu =
# 400 Pa, mu is recovered within 10 % and the held-out all-fours scan is
# predicted within 2 mm RMS; the output folder holds report.json and a
# calibrated case that simulate accepts. Bad inputs are refused with exit
# code 2, a message naming the option and no output folder.
# Usage: scan_calibrate.sh BREASTSIM
set -eu -o pipefail
BIN="$1"; PY=/usr/bin/python3
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
seed=0
for p in standing supine all_fours; do
  seed=$((seed + 1))
  "$BIN" -q synthetic-patient --volume 400 --ptosis 0.3 --lateral 0.1 --asymmetry 0.15 --mesh-size 0.01 \
    --noise 0.0005 --seed $seed --set tissue.mu=600 --posture $p --out "$p" >/dev/null
done
good=(standing/scan.stl --posture standing supine/scan.stl --posture supine --units mm --chest standing/chest.stl)

refuse() { # NAME MESSAGE ARGS...: exit 2, the message, no output folder
  local name="$1" msg="$2"; shift 2
  set +e; "$BIN" -q scan-calibrate "$@" --mesh-size 0.01 --out "bad_$name" >"$name.log" 2>&1; code=$?; set -e
  [ "$code" = 2 ] || { echo "FAIL: $name: exit $code, not 2"; cat "$name.log"; exit 1; }
  grep -q -- "$msg" "$name.log" || { echo "FAIL: $name: no '$msg' in:"; cat "$name.log"; exit 1; }
  [ ! -e "bad_$name" ] || { echo "FAIL: $name left output"; exit 1; }
  ls -d bad_"$name".partial-* >/dev/null 2>&1 && { echo "FAIL: $name left a staging folder"; exit 1; }
  return 0
}
refuse one_scan "at least two scans" standing/scan.stl --posture standing --units mm --chest standing/chest.stl
refuse postures "one --posture per scan" standing/scan.stl --posture standing supine/scan.stl --units mm \
  --chest standing/chest.stl
refuse same_posture "is given twice" standing/scan.stl --posture standing supine/scan.stl --posture standing \
  --units mm --chest standing/chest.stl
refuse no_chest "--chest is required" standing/scan.stl --posture standing supine/scan.stl --posture supine --units mm
refuse units "--units" "${good[@]/mm/cm}"
refuse fit_shape "--fit = R" "${good[@]}" --fit R
refuse fit_unknown "--fit" "${good[@]}" --fit nonsense
refuse fit_c_fixed "base.fixed = true" "${good[@]}" --fit mu,c --set base.fixed=true
refuse margin "--chest-margin = 0.5 is out of range" "${good[@]}" --chest-margin 0.5
refuse chest_rms "--max-chest-rms = 0.5 is out of range" "${good[@]}" --max-chest-rms 0.5
refuse predict_posture "one per held-out scan" "${good[@]}" --predict all_fours/scan.stl
refuse predict_fitted "a fitted scan is in this posture" "${good[@]}" --predict all_fours/scan.stl \
  --predict-posture supine
refuse missing_scan "no such file" standing/scan.stl --posture standing nothing.stl --posture supine --units mm \
  --chest standing/chest.stl

"$BIN" scan-calibrate "${good[@]}" --predict all_fours/scan.stl --predict-posture all_fours --mesh-size 0.01 \
  --out cal >cal.log 2>&1 || { echo "FAIL: scan-calibrate"; cat cal.log; exit 1; }
for f in report.json case.toml reference.msh scan.msh; do
  [ -s "cal/$f" ] || { echo "FAIL: no cal/$f"; exit 1; }
done
$PY - <<'PY'
import json
r = json.load(open("cal/report.json"))
mu = r["parameters"][0]
err = 100 * (mu["value"] / 600 - 1)
held = r["scans_predicted"][0]
print("mu %.1f Pa (truth 600, error %+.1f %%), 95 %% interval [%.1f, %.1f]; held-out %s RMS %.3f mm; %.1f s"
      % (mu["value"], err, mu["interval95"][0], mu["interval95"][1], held["posture"], held["rms_mm"],
         r["wall_time_s"]))
assert abs(err) < 10, "mu not within 10 %"
assert mu["interval95"][0] < mu["value"] < mu["interval95"][1]
assert held["posture"] == "all_fours" and held["rms_mm"] < 2.0, "held-out posture not within 2 mm RMS"
for s in r["scans_fitted"]:
    assert s["rms_mm"] < 1.0, s
chest = r["inputs"]["chest_wall"]  # the true chest is the plane y = 0
assert chest["source"] == "chest surface" and chest["plane_rms_m"] < 1e-6, chest
PY
"$BIN" -q simulate cal/case.toml --set output.xdmf=false --out sim >/dev/null \
  || { echo "FAIL: simulate of the calibrated case"; exit 1; }
grep -q '"all_fours"' sim/summary.json || { echo "FAIL: the calibrated case lacks the held-out posture"; exit 1; }
echo "scan_calibrate: OK"
