#!/usr/bin/env bash
# The skin surface written by `simulate` (surface_<posture>.json): corners on
# the neutral cap, outward triangles, P1 and P2, and mpirun -n 2 gives the
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
    $CHECK "$work/serial$order/surface_$p.json" 0.07 0.06
    $CHECK same "$work/serial$order/surface_$p.json" "$work/mpi$order/surface_$p.json" 1e-7
  done
done
echo "2 passed, 0 failed"
