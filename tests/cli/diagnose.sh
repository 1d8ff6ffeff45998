#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Missing-physics diagnosis on concealed data: a recording is made
# by the richer model (hidden candidate HIDDEN switched on, or none for the
# control) on a finer P2 mesh, with noise, at random skin points; `diagnose`
# sees only the recording and the current model. Asserts: the right
# candidate is named (and nothing else), the hidden value lies in the
# reported 95 % interval, the fit improves to the noise level; the control
# produces no discovery. Also: bad inputs are refused with no output.
# Usage: diagnose.sh BREASTSIM CASES_DIR HIDDEN
set -euo pipefail
bin="$1"; cases="$2"; hidden="$3"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
case_file="$cases/default.toml"
sets=()
case "$hidden" in
  skin) sets=(--set terms.skin=false) ;;
  base_springs) sets=(--set base.fixed=true --set terms.base_springs=false) ;;
esac
hide=()
[ "$hidden" != control ] && hide=(--hidden "$hidden")

# The truth: P2 at 6 mm (the diagnosis: P2 at 12 mm, its check mesh 8 mm).
"$bin" -q record "$case_file" "${sets[@]}" --set geometry.order=2 "${hide[@]}" --seed 7 --mesh-size 0.006 \
  --out "$work/recording.json"
"$bin" -q diagnose "$work/recording.json" --case "$case_file" "${sets[@]}" --set output.pictures=full \
  --out "$work/out" \
  > "$work/log.txt" 2>&1 || { cat "$work/log.txt"; exit 1; }
cat "$work/log.txt"

/usr/bin/python3 - "$work" "$hidden" <<'PY'
import json, sys
from pathlib import Path
work, hidden = Path(sys.argv[1]), sys.argv[2]
rec = json.loads((work / "recording.json").read_text())
d = json.loads((work / "out" / "diagnosis.json").read_text())
assert "truth" in rec and rec["truth"]["hidden"] == (None if hidden == "control" else hidden)
found = d["discovered"]
# Each term found names its physics (a family of forms names the family).
assert d["discovered_physics"] == found, (d["discovered_physics"], found)
assert [f["term"] for f in d["discovered_forms"]] == found, d["discovered_forms"]
assert all(f["physics"] == f["term"] and f["parameter"] for f in d["discovered_forms"]), d["discovered_forms"]
first, final = d["rounds"][0]["fit"], d["final"]
rms = lambda f: sum(p["rms_mm"] for p in f["postures"]) / len(f["postures"])
if hidden == "control":
    assert found == [], f"control: false discovery {found}"
    assert "explains the recording" in d["verdict"], d["verdict"]
    # Nothing found: the tissue values still carry their numerical part (finer mesh).
    assert len(d["se_log_numerical"]) == len(final["parameters"]) > 0, d["se_log_numerical"]
else:
    assert found == [hidden], f"hidden {hidden}: named {found}"
    par = rec["truth"]["parameter"]
    p = next(q for q in final["parameters"] if q["name"] == par)
    lo, hi = p["interval95"]
    assert lo <= rec["truth"]["value"] <= hi, f"{par}: truth {rec['truth']['value']} not in [{lo}, {hi}]"
    assert rms(final) < rms(first), (rms(first), rms(final))
    # Where: the systematic residual was located before the discovery.
    assert d["rounds"][0]["regions"], "no region of systematic residual was reported"
    assert d["rounds"][0]["scores"][0]["candidate"] in [r["candidate"] for r in d["rounds"][0]["refits"]]
# The remaining residual is at the noise level.
assert final["gof_p"] > 1e-3, f"final fit not at the noise level: p = {final['gof_p']}"
for name in ["diagnosis.txt", "residuals.json", "case.diagnosed.toml", "residual_rms.png",
             "index.html", "overview.png"] + \
        [f"residuals_{p['name']}.{ext}" for p in rec["postures"] for ext in ("png", "xdmf")] + \
        [f"view_{p['name']}.png" for p in rec["postures"]]:
    f = work / "out" / name
    assert f.is_file() and f.stat().st_size > 1000, f"missing or empty: {name}"
# The 3D page can colour the final skin by |residual| before/after.
for p in rec["postures"]:
    surf = json.loads((work / "out" / f"surface_{p['name']}.json").read_text())
    n = len(surf["vertices"]) // 3
    for f in ("abs_residual_before_mm", "abs_residual_after_mm", "displacement_mm"):
        assert len(surf["fields"][f]) == n, f
    assert max(surf["fields"]["abs_residual_before_mm"]) > 0
print(f"OK: {hidden}: named {found or 'nothing'}")
PY

# The diagnosed case is a valid case for `simulate` (terms switched on).
if [ "$hidden" = suspensory_ligament ]; then
  grep -q "suspensory_ligament = true" "$work/out/case.diagnosed.toml"
fi

# Bad inputs: clear message, exit code 2, no output folder.
expect_fail() {
  local what="$1"; shift
  if "$bin" -q diagnose "$@" --out "$work/bad" > "$work/bad.txt" 2>&1; then
    echo "FAIL: $what accepted"; exit 1
  fi
  code=$?
  grep -q -e "$what" "$work/bad.txt" || { echo "FAIL: message lacks '$what':"; cat "$work/bad.txt"; exit 1; }
  [ ! -e "$work/bad" ] || { echo "FAIL: partial output for $what"; exit 1; }
}
if [ "$hidden" = control ]; then
  # The recording as calibration data (3D surface points): mu and c
  # with intervals that hold the truth, and a calibrated case.
  "$bin" -q calibrate "$work/recording.json" --case "$case_file" --fit mu,c --out "$work/cal" > /dev/null
  /usr/bin/python3 - "$work" <<'PY'
import json, sys
from pathlib import Path
work = Path(sys.argv[1])
truth = json.loads((work / "recording.json").read_text())["truth"]["case"]
final = json.loads((work / "cal" / "diagnosis.json").read_text())["final"]
for p in final["parameters"]:
    key = {"mu": "tissue.mu", "c": "base.c"}[p["name"]]
    lo, hi = p["interval95"]
    assert lo <= truth[key] <= hi, f"{p['name']}: truth {truth[key]} not in [{lo}, {hi}]"
    print(f"calibrate from a recording: {p['name']} = {p['value']:.4g} [{lo:.4g}, {hi:.4g}], truth {truth[key]}")
PY
  grep -q "mesh_size = 0.008" "$work/cal/calibrated.toml"
  # Two MPI ranks give the same verdict and the same fit (to the finite-difference noise).
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun -n 2 "$bin" -q diagnose \
    "$work/recording.json" --case "$case_file" --out "$work/out_mpi" > /dev/null
  /usr/bin/python3 - "$work" <<'PY'
import json, sys
from pathlib import Path
work = Path(sys.argv[1])
a = json.loads((work / "out" / "diagnosis.json").read_text())
b = json.loads((work / "out_mpi" / "diagnosis.json").read_text())
assert a["discovered"] == b["discovered"] == [], (a["discovered"], b["discovered"])
for pa, pb in zip(a["final"]["parameters"], b["final"]["parameters"]):
    assert abs(pa["value"] / pb["value"] - 1) < 1e-3, (pa, pb)
print("mpirun -n 2: same verdict, mu", a["final"]["parameters"][0]["value"], b["final"]["parameters"][0]["value"])
PY
  expect_fail "does not exist" "$work/missing.json"
  expect_fail "unknown candidate physics 'dark_matter'" "$work/recording.json" --candidates dark_matter
  expect_fail "alpha" "$work/recording.json" --alpha 2
  expect_fail "--order = 3 is out of range" "$work/recording.json" --order 3
  expect_fail "--mesh-size = -0.01 m is out of range" "$work/recording.json" --mesh-size -0.01
  expect_fail "--min-separation-z = -1 is out of range" "$work/recording.json" --min-separation-z -1
  expect_fail "--jackknife-patches = 11 is out of range" "$work/recording.json" --jackknife-patches 11
  sed 's/"noise_sigma":[^,]*/"noise_sigma":-1/' "$work/recording.json" > "$work/neg.json"
  expect_fail "key 'noise_sigma' = -1" "$work/neg.json"
fi
echo "diagnose $hidden: OK"
