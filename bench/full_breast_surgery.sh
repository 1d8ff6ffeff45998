#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Surgery on the real shape (docs/SCANS.md "Surgery on a full breast"): the
# five synthetic patients of bench/scan_round_trip.sh (true chest wall given),
# scan -> scan-model -> neutral-state -> surgery (standing), serially and on
# 2 MPI ranks: both suture gaps, volumes, the keel nodes whose mirror images
# lie beyond the other keel face (and how far, in its cells' reference
# coordinates), wall times. The incision is the
# default case's scaled to each breast (R: its mean footprint radius, H: its
# nipple height, geometry.R and geometry.H of case.reference.toml):
# s = 0.29 R, h = 0.42 H, d = 0.64 R (20, 25 and 45 mm on the 70 x 60 mm cap), a = 30 deg.
# Usage: bench/full_breast_surgery.sh BUILD_DIR [MESH_SIZE (m, default 0.01)]
set -eu -o pipefail
BIN="$(cd "$1" && pwd)/breastsim"; H="${2:-0.01}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
patients=("200 0.1 0 0" "400 0.3 0.1 0.15" "700 0.5 0.2 0.1" "1000 0.4 -0.1 0.3" "1500 0.6 0.15 0.2")
printf "%-28s %8s %9s %9s %9s %9s %9s %8s %8s %8s %8s %8s\n" patient tets_kept pre_cm3 resected mesh_cm3 keel_mm \
  chest_mm fit_mm extended max_ext serial_s ranks2_s
k=0
for p in "${patients[@]}"; do
  k=$((k + 1)); set -- $p
  "$BIN" -q synthetic-patient --volume "$1" --ptosis "$2" --lateral "$3" --asymmetry "$4" --mesh-size "$H" \
    --seed "$k" --format stl --out "p$k" >/dev/null
  "$BIN" -q scan-model "p$k/scan.stl" --units mm --posture standing --chest "p$k/chest.stl" --mesh-size "$H" \
    --out "m$k" >/dev/null
  "$BIN" -q neutral-state "m$k/case.toml" --posture standing --out "n$k" >/dev/null
  plan=($(/usr/bin/python3 - "n$k/case.reference.toml" <<'PY'
import sys, tomllib
g = tomllib.load(open(sys.argv[1], "rb"))["geometry"]
print("--set incision.s=%.4f --set incision.h=%.4f --set incision.d=%.4f" % (0.29 * g["R"], 0.42 * g["H"], 0.64 * g["R"]))
PY
))
  t0=$(date +%s.%N)
  "$BIN" -q surgery "n$k/case.reference.toml" "${plan[@]}" --set output.xdmf=false --out "s$k" >/dev/null
  t1=$(date +%s.%N)
  mpirun -n 2 "$BIN" -q surgery "n$k/case.reference.toml" "${plan[@]}" --set output.xdmf=false --out "r$k" >/dev/null
  t2=$(date +%s.%N)
  /usr/bin/python3 - "s$k/summary.json" "r$k/summary.json" "$p" "$t0" "$t1" "$t2" <<'PY'
import json, sys
s, r = (json.load(open(f)) for f in sys.argv[1:3])
t0, t1, t2 = map(float, sys.argv[4:7])
g = s["suture"]
assert abs(s["resected_volume_m3"] / r["resected_volume_m3"] - 1) < 1e-9, "serial and 2 ranks differ"
print("%-28s %8d %9.1f %9.1f %9.1f %9.4f %9.4f %8.3f %8d %8.3f %8.1f %8.1f" % (
    sys.argv[3], s["mesh_incised"]["cells"], 1e6 * s["volume_pre_m3"], 1e6 * s["resected_volume_m3"],
    1e6 * s["resected_volume_mesh_m3"], 1e3 * g["max_gap_keel_m"], 1e3 * g["max_gap_chest_m"],
    1e3 * s["skin_fit_rms_m"], g["keel_nodes_extended"], g["keel_max_extension"], t1 - t0, t2 - t1))
PY
done
