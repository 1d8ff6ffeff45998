#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# The skin surface written by `simulate` (surface_<posture>.json): corners on
# the neutral cap, outward triangles, P1 and P2, flagged as a half model to
# mirror; a full breast (a synthetic patient's scan through scan-model) with
# corners of both signs of x and no mirror flag; and mpirun -n 2 gives the
# same surface as a serial run.
# Usage: surface.sh BREASTSIM CASES_DIR
set -eu
BIN="$1"; CASES="$2"; HERE="$(cd "$(dirname "$0")" && pwd)"
CHECK="/usr/bin/python3 $HERE/check_surface.py"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
for order in 1 2; do
  args=(--set geometry.mesh_size=0.012 --set geometry.order=$order --set postures.names=standing,supine)
  "$BIN" -q simulate "$CASES/default.toml" "${args[@]}" --out "$work/serial$order" >/dev/null
  mpirun -n 2 "$BIN" -q simulate "$CASES/default.toml" "${args[@]}" --out "$work/mpi$order" >/dev/null
  for p in standing supine; do
    # P1: corners on the sphere; P2: points inside the curved triangles, within 0.1 mm
    $CHECK "$work/serial$order/surface_$p.json" 0.07 0.06 "$([ $order = 1 ] && echo 1e-6 || echo 1e-4)"
    $CHECK same "$work/serial$order/surface_$p.json" "$work/mpi$order/surface_$p.json" 1e-7
  done
done
"$BIN" -q synthetic-patient --volume 400 --ptosis 0.3 --lateral 0.1 --asymmetry 0.15 --mesh-size 0.01 \
  --out "$work/patient" >/dev/null
"$BIN" -q scan-model "$work/patient/scan.stl" --units mm --posture standing --mesh-size 0.012 \
  --out "$work/scan" >/dev/null
args=(--set postures.names=standing,supine --set output.xdmf=false)
"$BIN" -q simulate "$work/scan/case.toml" "${args[@]}" --out "$work/full_serial" >/dev/null
mpirun -n 2 "$BIN" -q simulate "$work/scan/case.toml" "${args[@]}" --out "$work/full_mpi" >/dev/null
for p in standing supine; do
  $CHECK full "$work/full_serial/surface_$p.json"
  $CHECK full "$work/full_mpi/surface_$p.json"
  $CHECK same "$work/full_serial/surface_$p.json" "$work/full_mpi/surface_$p.json" 1e-7
done
echo "3 passed, 0 failed"
