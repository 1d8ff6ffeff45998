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
echo "2 passed, 0 failed"
