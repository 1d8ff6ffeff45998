#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# `breastsim measure` + `breastsim calibrate` end to end on a coarse mesh:
# the calibrated case must be accepted by `breastsim simulate` unchanged;
# bad measurement files and unidentifiable requests exit with code 2 and
# leave no output folder.
set -u
BIN="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")" # absolute: the checks run in a scratch folder
CHECK="/usr/bin/python3 $(cd "$(dirname "$0")/../viewer" && pwd)/png_check.py"
FORMS="$(cd "$(dirname "$0")/../../forms" && pwd)"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }

printf '[geometry]\nmesh_size = 0.016\n[tissue]\nmu = 300.0\n' > start.toml
printf '[geometry]\nmesh_size = 0.016\n' > truth.toml
"$BIN" -q measure truth.toml --mesh-size 0.012 --noise 0.0005 --seed 3 --out m.json || fail "measure"
"$BIN" -q calibrate m.json --case start.toml --fit mu --max-evals 30 --size 640x480 \
  --set output.pictures=full --out fit \
  >calib.out 2>calib.err || { fail "calibrate"; cat calib.err; }
[ -f fit/calibrated.toml ] && [ -f fit/report.json ] || fail "calibrate outputs missing"
# Pictures next to the JSON: plots of the fit and the calibrated breast per measured posture.
for png in misfit_history measurements overview view_standing view_supine view_all_fours; do
  $CHECK size "fit/$png.png" 640 480 || fail "picture $png.png"
done
for png in misfit_history measurements view_standing view_supine; do
  $CHECK drawn "fit/$png.png" || fail "picture $png.png is blank"
done
$CHECK differ fit/view_standing.png fit/view_supine.png || fail "standing and supine pictures are the same"
$CHECK differ fit/misfit_history.png fit/measurements.png || fail "the two plots are the same"
[ -f fit.checkpoint.json ] || fail "no checkpoint written"
grep -q "mu " calib.out || fail "no result table"
"$BIN" -q simulate fit/calibrated.toml --out sim >sim.out 2>sim.err || { fail "simulate of calibrated.toml"; cat sim.err; }
echo "ok   calibrate -> simulate: $(grep '^mu' calib.out)"

expect_error() { # name, message fragment, measurement JSON, calibrate args...
  local name="$1" frag="$2" json="$3"; shift 3
  printf '%s' "$json" > "$name.json"
  "$BIN" -q calibrate "$name.json" --out "out_$name" "$@" >/dev/null 2>"$name.err"
  local code=$?
  [ "$code" -eq 2 ] || { fail "$name: exit code $code (expected 2)"; cat "$name.err"; return; }
  grep -qF -- "$frag" "$name.err" || { fail "$name: message lacks '$frag'"; cat "$name.err"; return; }
  ! ls -d out_"$name"* >/dev/null 2>&1 || { fail "$name: output left behind"; return; }
  echo "ok   $name: $(head -c 160 "$name.err")"
}
ok='{"units": "SI", "postures": [{"name": "standing", "projection": 0.06}]}'
expect_error units "'units' = \"mm\"" '{"units": "mm", "postures": [{"name": "standing", "projection": 0.06}]}'
expect_error no_postures "'postures' is missing" '{"units": "SI", "base_perimeter": 0.43}'
expect_error negative "'base_perimeter' = -0.43" '{"units": "SI", "base_perimeter": -0.43, "postures": [{"name": "supine", "projection": 0.05}]}'
expect_error nan "not valid JSON" '{"units": "SI", "postures": [{"name": "standing", "projection": NaN}]}'
expect_error rho_mu "only mu/rho is identifiable" "$ok" --fit rho,mu
expect_error algorithm "--algorithm 'newton' is unknown" "$ok" --algorithm newton
expect_error resume "checkpoint" "$ok" --resume --checkpoint "$work/none.json"
expect_error size "--size '12x7'" "$ok" --size 12x7
expect_error correction "--correction-mesh-size = 0.02" "$ok" --correction-mesh-size 0.02

# The --fit names and the diagnosis candidates the binary knows are those
# the terms declare in forms/ (FIT, GEOMETRY_FIT, CANDIDATE).
declared=$(cd "$FORMS" && PYTHONPATH="$FORMS" BREASTSIM_DEGREE=1 /usr/bin/python3 -c '
import model
print(", ".join(model.FIT_ALIASES))
print("; ".join(n + ": " + c["parameter"] + " [" + c["unit"] + "]" for n, c in model.CANDIDATES.items()))
') || fail "forms/model.py cannot be imported"
fit_names=$(sed -n 1p <<<"$declared"); candidates=$(sed -n 2p <<<"$declared")
"$BIN" calibrate --help | tr -s ' \n' ' ' | grep -qF -- "comma separated: $fit_names" \
  && echo "ok   --fit names as declared: $fit_names" || fail "calibrate --help lacks the declared --fit names '$fit_names'"
"$BIN" record --help | tr -s ' \n' ' ' | grep -qF -- "its parameter ($candidates)" \
  && echo "ok   candidates as declared: $candidates" || fail "record --help lacks the declared candidates '$candidates'"

[ "$fails" -eq 0 ] && echo "all calibrate CLI checks passed" || { echo "$fails failures"; exit 1; }
