#!/usr/bin/env bash
# mpirun -n 2 gives the same observables as a serial run (to solver tolerance).
set -eu
BIN="$1"; CASES="$2"; HERE="$(cd "$(dirname "$0")" && pwd)"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
for order in 1 2; do
  "$BIN" -q simulate "$CASES/default.toml" --set geometry.mesh_size=0.012 --set geometry.order=$order \
    --out "$work/serial$order"
  mpirun -n 2 "$BIN" -q simulate "$CASES/default.toml" --set geometry.mesh_size=0.012 \
    --set geometry.order=$order --out "$work/mpi$order"
  python3 -c "import json; assert json.load(open('$work/mpi$order/summary.json'))['mpi_ranks'] == 2"
  /usr/bin/python3 "$HERE/compare_json.py" "$work/mpi$order/summary.json" "$work/serial$order/summary.json" 1e-7 1e-10
done
# Grid sequencing (solver.coarse_start): every rank solves the coarse mesh
# itself and interpolates at its own nodes; the result must not depend on it.
coarse=(--set geometry.mesh_size=0.005 --set solver.coarse_mesh_size=0.01 --set postures.names=standing,supine)
"$BIN" -q simulate "$CASES/default.toml" "${coarse[@]}" --out "$work/serial_coarse"
mpirun -n 2 "$BIN" -q simulate "$CASES/default.toml" "${coarse[@]}" --out "$work/mpi_coarse"
/usr/bin/python3 -c "
import json
for p in json.load(open('$work/mpi_coarse/summary.json'))['postures']:
    assert p['coarse_start'] and p['coarse_newton_iterations'] > 0, p"
/usr/bin/python3 "$HERE/compare_json.py" "$work/mpi_coarse/summary.json" "$work/serial_coarse/summary.json" 1e-7 1e-10
# The AMG path (GMRES + GAMG, finest level smoothed by SOR: on 2 ranks a
# local symmetric sweep per rank, so the Krylov counts differ, not the result).
amg=(--set solver.linear=amg --set postures.names=standing,supine)
"$BIN" -q simulate "$CASES/default.toml" "${amg[@]}" --out "$work/serial_amg"
mpirun -n 2 "$BIN" -q simulate "$CASES/default.toml" "${amg[@]}" --out "$work/mpi_amg"
/usr/bin/python3 "$HERE/compare_json.py" "$work/mpi_amg/summary.json" "$work/serial_amg/summary.json" 1e-7 1e-10
echo "4 passed, 0 failed"
