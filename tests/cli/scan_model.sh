#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# `breastsim scan-model` (docs/SCANS.md): every bad scan or option is refused
# with exit code 2, a message naming the defect and no output folder; a
# spherical cap's scan and a synthetic patient's (holes, 0.5 mm noise) go
# scan -> scan-model -> neutral-state -> simulate and reproduce the scanned
# skin (bench/scan_compare.py: loaded_rms_mm < 0.1 off the chest, the
# reference within 1 mm RMS of the truth, 0.5 mm with the true chest wall
# given by --chest). The case scan-model writes and the case.reference.toml
# neutral-state writes are accepted by measure and calibrate (mu recovered
# from noiseless measurements at 600 Pa; the cap's shape keys and a finer
# correction mesh refused, exit 2), the calibrated case by simulate, and
# view draws a scan case's result.
# Usage: scan_model.sh BREASTSIM SOURCE_DIR
set -eu -o pipefail
BIN="$1"; SRC="$2"; PY=/usr/bin/python3
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$BIN" -q synthetic-patient --volume 400 --ptosis 0.3 --lateral 0.1 --asymmetry 0.15 --mesh-size 0.01 \
  --format stl-ascii --out patient >patient.log
[ -s patient/scan.stl ] || { echo "FAIL: no synthetic scan"; exit 1; }

# Bad scans, written from the good one.
$PY - <<'PY'
import re, struct
text = open("patient/scan.stl").read()
facets = re.findall(r"facet normal.*?endfacet\n", text, re.S)
head, tail = "solid s\n", "endsolid s\n"
def stl(name, fs): open(name, "w").write(head + "".join(fs) + tail)
stl("duplicated.stl", facets + [facets[10]])
v = re.findall(r"vertex .*\n", facets[20])
stl("reversed.stl", facets[:20] + [facets[20].replace(v[1], "TMP").replace(v[2], v[1]).replace("TMP", v[2])] + facets[21:])
stl("nan.stl", facets[:5] + [re.sub(r"vertex (\S+)", "vertex nan", facets[5], 1)] + facets[6:])
far = "facet normal 0 0 1\n outer loop\n  vertex 220 50 1200\n  vertex 230 50 1200\n  vertex 220 60 1200\n endloop\nendfacet\n"
stl("pieces.stl", facets + [far])
# a spike: the top vertex of facet 300 (and every facet sharing it) moved 20 mm along y
p = re.findall(r"vertex (\S+) (\S+) (\S+)", facets[300])[0]
old = "vertex %s %s %s" % p
new = "vertex %s %.9g %s" % (p[0], float(p[1]) + 20, p[2])
stl("spike.stl", [f.replace(old, new) for f in facets])
# a big hole: the facets within 20 mm of the most anterior vertex removed
pts = [tuple(map(float, m)) for m in re.findall(r"vertex (\S+) (\S+) (\S+)", text)]
top = max(pts, key=lambda q: q[1])
def near(f):
    return any(sum((a - b) ** 2 for a, b in zip(tuple(map(float, m)), top)) < 400 for m in re.findall(r"vertex (\S+) (\S+) (\S+)", f))
stl("hole.stl", [f for f in facets if not near(f)])
stl("few.stl", facets[:30])
open("empty.obj", "w").write("# nothing\n")
open("cloud.obj", "w").write("".join("v %g %g %g\n" % q for q in sorted(set(pts))))
b = open("patient/scan.stl").read()
open("scan.xyz", "w").write(b)
# a truncated binary STL
data = bytearray(80) + struct.pack("<I", 1000) + bytearray(50 * 10)
open("truncated.stl", "wb").write(bytes(data))
# the true chest (the plane y = 50 mm of the scanner) bent about the cranial axis: y - 50 = -(x - 100)^2 / (2 R)
raw = open("patient/chest.stl", "rb").read()
count = struct.unpack("<I", raw[80:84])[0]
for name, R in (("ribs.stl", 250.0), ("gentle.stl", 1000.0)):
    out = bytearray(raw[:84])
    for k in range(count):
        rec = raw[84 + 50 * k: 134 + 50 * k]
        v = list(struct.unpack("<12f", rec[:48]))
        for c in range(3, 12, 3):
            v[c + 1] = 50.0 - (v[c] - 100.0) ** 2 / (2 * R)
        out += struct.pack("<12f", *v) + rec[48:]
    open(name, "wb").write(bytes(out))
PY

refuse() { # NAME MESSAGE ARGS...: exit 2, the message, no output folder
  local name="$1" msg="$2"; shift 2
  set +e; "$BIN" -q scan-model "$@" --out "bad_$name" >"$name.log" 2>&1; code=$?; set -e
  [ "$code" = 2 ] || { echo "FAIL: $name: exit $code, not 2"; cat "$name.log"; exit 1; }
  grep -q -- "$msg" "$name.log" || { echo "FAIL: $name: no '$msg' in:"; cat "$name.log"; exit 1; }
  [ ! -e "bad_$name" ] || { echo "FAIL: $name left output"; exit 1; }
  ls -d bad_"$name".partial-* >/dev/null 2>&1 && { echo "FAIL: $name left a staging folder"; exit 1; }
  return 0
}
refuse missing "no such file" none.stl --units mm
refuse format "unknown scan format '.xyz'" scan.xyz --units mm
refuse truncated "truncated binary STL" truncated.stl --units mm
refuse empty "empty" empty.obj --units mm
refuse nan "non-finite x coordinate" nan.stl --units mm
refuse few "too few points" few.stl --units mm
refuse units "wrong units?" patient/scan.stl --units m
refuse duplicated "duplicated triangle" duplicated.stl --units mm
refuse reversed "inconsistent orientation" reversed.stl --units mm
refuse pieces "disconnected pieces" pieces.stl --units mm
refuse spike "spike: vertex" spike.stl --units mm
refuse hole "hole:" hole.stl --units mm
refuse cloud "a point cloud has no open boundary" cloud.obj --units mm
refuse unit_option "the unit of the scan's coordinates must be stated" patient/scan.stl --units cm
refuse nipple "from the nearest point of the scan" patient/scan.stl --units mm --nipple 0,0,0
refuse up "nearly along the chest normal" patient/scan.stl --units mm --up 0,1,0
refuse size "--mesh-size = 0.5 is out of range" patient/scan.stl --units mm --mesh-size 0.5
refuse chest_rms_option "--max-chest-rms = 0.5 is out of range" patient/scan.stl --units mm --max-chest-rms 0.5
refuse curved_chest "chest too curved for a planar base" patient/scan.stl --units mm --chest ribs.stl
"$BIN" -q scan-model patient/scan.stl --units mm --chest gentle.stl --mesh-size 0.012 --out gentle_model >/dev/null
$PY - gentle_model/summary.json <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))["chest"]
r = c["curvature_radii_m"][0]
if not (c["source"] == "chest surface" and 0.0005 < c["plane_rms_m"] < 0.003 and 0.9 < r < 1.1):
    sys.exit("FAIL: the gently curved chest (R = 1 m) measured as %s" % c)
PY

# Round trips: the synthetic patient, then a cap's scan (R = 70 mm, H = 60 mm).
trip() { # NAME SCAN TRUTH [SCAN-MODEL OPTIONS...]
  local name="$1" scan="$2" truth="$3"; shift 3
  set -- "$name" "$scan" "$truth" "$@"
  "$BIN" -q scan-model "$2" --units mm --posture standing --mesh-size 0.01 "${@:4}" --out "$1_model" >"$1_model.log"
  "$BIN" -q neutral-state "$1_model/case.toml" --posture standing --out "$1_neutral" >"$1_neutral.log"
  for f in "$1_model/scan.xdmf" "$1_model/scan.h5" "$1_neutral/neutral_standing.xdmf"; do
    [ -s "$f" ] || { echo "FAIL: $f missing (ParaView files)"; exit 1; }
  done
  grep -q 'Name="mesh_tags"' "$1_model/scan.xdmf" || { echo "FAIL: scan.xdmf has no facet tags"; exit 1; }
  "$BIN" -q simulate "$1_neutral/case.reference.toml" --set postures.names=standing --set output.xdmf=false \
    --out "$1_forward" >"$1_forward.log"
  $PY "$SRC/bench/scan_compare.py" "$3" "$1_model" "$1_neutral" "$1_forward" | tee "$1.json"
}
trip patient patient/scan.stl patient
trip chest patient/scan.stl patient --chest patient/chest.stl

for case in patient_model/case.toml patient_neutral/case.reference.toml; do
  name=$(basename "$(dirname "$case")")
  "$BIN" -q measure "$case" --set tissue.mu=600 --set postures.names=standing,supine --noise 0 --sigma 0.0005 \
    --out "$name.measured.json" >/dev/null
  "$BIN" -q calibrate "$name.measured.json" --case "$case" --fit mu --out "${name}_cal" >/dev/null
  $PY - "${name}_cal/report.json" <<'PY'
import json, sys
mu = [p for p in json.load(open(sys.argv[1]))["fit"] if p["name"] == "mu"][0]["fitted"]
if abs(mu / 600 - 1) > 0.01:
    sys.exit("FAIL: calibrate on %s: mu = %g Pa, not 600" % (sys.argv[1], mu))
PY
  "$BIN" -q simulate "${name}_cal/calibrated.toml" --set postures.names=standing --set output.xdmf=false \
    --out "${name}_cal_simulated" >/dev/null
done
set +e
"$BIN" -q calibrate patient_model.measured.json --case patient_model/case.toml --fit mu,H --out bad_fit_H >fit_H.log 2>&1
code_H=$?
"$BIN" -q calibrate patient_model.measured.json --case patient_model/case.toml --fit mu --correction-mesh-size 0.005 \
  --out bad_correction >correction.log 2>&1
code_c=$?
set -e
[ "$code_H" = 2 ] && grep -q "geometry.mesh_file" fit_H.log && [ ! -e bad_fit_H ] \
  || { echo "FAIL: calibrate --fit H of a scan case: exit $code_H"; cat fit_H.log; exit 1; }
[ "$code_c" = 2 ] && grep -q -- "--correction-mesh-size" correction.log && [ ! -e bad_correction ] \
  || { echo "FAIL: calibrate --correction-mesh-size of a scan case: exit $code_c"; cat correction.log; exit 1; }
"$BIN" -q view patient_forward --size 400x300 >/dev/null
[ -s patient_forward/index.html ] && [ -s patient_forward/view_standing.png ] \
  || { echo "FAIL: view wrote no page or picture of the scan case"; exit 1; }
$PY - "$SRC" <<'PY'
import math, struct, sys
R, H = 70.0, 60.0
Rs = (R * R + H * H) / (2 * H); yc = H - Rs; nr, nt = 24, 72
pts = [(0.0, H, 0.0)]
for i in range(1, nr + 1):
    for j in range(nt):
        x, z = R * i / nr * math.cos(2 * math.pi * j / nt), R * i / nr * math.sin(2 * math.pi * j / nt)
        pts.append((x, max(0.0, yc + math.sqrt(Rs * Rs - x * x - z * z)), z))
idx = lambda i, j: 0 if i == 0 else 1 + (i - 1) * nt + j % nt
tris = [(0, idx(1, j + 1), idx(1, j)) for j in range(nt)]
for i in range(1, nr):
    for j in range(nt):
        tris += [(idx(i, j), idx(i, j + 1), idx(i + 1, j + 1)), (idx(i, j), idx(i + 1, j + 1), idx(i + 1, j))]
with open("cap.stl", "wb") as f:
    f.write(bytes(80) + struct.pack("<I", len(tris)))
    for t in tris:
        f.write(struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *pts[k]) for k in t) + b"\0\0")
PY
trip cap cap.stl -
$PY - <<'PY'
import json, sys
p, c, w = json.load(open("patient.json")), json.load(open("cap.json")), json.load(open("chest.json"))
bad = []
if p["loaded_rms_mm"] > 0.1 or c["loaded_rms_mm"] > 0.1:
    bad.append("the loaded skin is not reproduced within 0.1 mm RMS")
if p["reference_rms_mm"] > 1.0:
    bad.append("the reference is not within 1 mm RMS of the truth")
if w["reference_rms_mm"] > 0.5 or w["loaded_rms_mm"] > 0.1:
    bad.append("with the true chest wall, the reference is not within 0.5 mm RMS of the truth")
if bad:
    sys.exit("FAIL: " + "; ".join(bad))
PY
echo "scan_model: ok"
