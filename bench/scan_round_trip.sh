#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Round trip of scanned breasts (docs/SCANS.md): five synthetic patients
# (200 to 1500 cm^3, ptosis, lateral turn, asymmetry; holes, 0.5 mm noise)
# and a spherical cap's scan go scan -> scan-model -> neutral-state ->
# simulate; prints per breast the times and bench/scan_compare.py's RMS numbers.
# With CHEST = chest, the patients' true chest wall (chest.stl) is given
# (--chest) instead of the plane fitted through the footprint.
# MESH_SIZE_M: scan-model's --mesh-size (0: by the volume); the truth is meshed at 6 mm.
# Usage: bash bench/scan_round_trip.sh BUILD_DIR [MESH_SIZE_M] [chest]
set -eu -o pipefail
BIN="$(cd "$1" && pwd)/breastsim"; H="${2:-0.006}"; CHEST="${3:-}"
SRC="$(cd "$(dirname "$0")/.." && pwd)"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
run() { # NAME SCAN TRUTH
  local t0 t1 t2
  t0=$(date +%s.%N)
  local chest=()
  [ "$CHEST" = chest ] && [ "$3" != - ] && chest=(--chest "$3/chest.stl")
  "$BIN" -q scan-model "$2" --units mm --posture standing --mesh-size "$H" "${chest[@]}" --out "$1_m" >/dev/null
  "$BIN" -q neutral-state "$1_m/case.toml" --posture standing --out "$1_n" >/dev/null \
    || { echo "$1: neutral-state refused (exit $?)"; return 0; }
  t1=$(date +%s.%N)
  "$BIN" -q simulate "$1_n/case.reference.toml" --set postures.names=standing,supine,all_fours \
    --set output.xdmf=false --out "$1_f" >/dev/null
  t2=$(date +%s.%N)
  echo "$1 scan->neutral $(echo "$t1 - $t0" | bc) s, three postures $(echo "$t2 - $t1" | bc) s, tetrahedra $(/usr/bin/python3 -c "import json;print(json.load(open('$1_m/summary.json'))['tetrahedra'])")"
  "$BIN" -q simulate "$1_n/case.reference.toml" --set postures.names=standing --set output.xdmf=false \
    --out "$1_s" >/dev/null
  /usr/bin/python3 "$SRC/bench/scan_compare.py" "$3" "$1_m" "$1_n" "$1_s"
}
i=0
for shape in "200 0.1 0.0 0.0" "400 0.3 0.1 0.15" "700 0.5 0.2 0.1" "1000 0.4 -0.1 0.3" "1500 0.6 0.15 0.2"; do
  set -- $shape; i=$((i + 1))
  "$BIN" -q synthetic-patient --volume "$1" --ptosis "$2" --lateral "$3" --asymmetry "$4" --mesh-size 0.006 \
    --seed "$i" --out "p$i" >/dev/null
  echo "patient $i: volume $1 cm3, ptosis $2, lateral $3, asymmetry $4"
  run "p$i" "p$i/scan.stl" "p$i"
done
/usr/bin/python3 - <<'PY'
import math, struct
R, H = 70.0, 60.0
Rs = (R * R + H * H) / (2 * H); yc = H - Rs; nr, nt = 30, 96
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
echo "cap R = 70 mm, H = 60 mm (taken as scanned standing)"
run cap cap.stl -
