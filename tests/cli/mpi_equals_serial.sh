#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# mpirun -n 2 gives the same observables as a serial run (to solver tolerance).
set -eu
BIN="$1"; CASES="$2"; HERE="$(cd "$(dirname "$0")" && pwd)"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# serial_vs_mpi NAME SETTINGS...: the default case with SETTINGS, serially
# (into $work/serial_NAME) and on 2 ranks ($work/mpi_NAME), observables compared.
serial_vs_mpi() {
  local name="$1"; shift
  "$BIN" -q simulate "$CASES/default.toml" "$@" --out "$work/serial_$name"
  mpirun -n 2 "$BIN" -q simulate "$CASES/default.toml" "$@" --out "$work/mpi_$name"
  python3 -c "import json; assert json.load(open('$work/mpi_$name/summary.json'))['mpi_ranks'] == 2"
  /usr/bin/python3 "$HERE/compare_json.py" "$work/mpi_$name/summary.json" "$work/serial_$name/summary.json" 1e-7 1e-10
}
for order in 1 2; do
  serial_vs_mpi "p$order" --set geometry.mesh_size=0.012 --set geometry.order=$order
done
# Grid sequencing (solver.coarse_start): every rank solves the coarse mesh
# itself and interpolates at its own nodes; the result must not depend on it.
serial_vs_mpi coarse --set geometry.mesh_size=0.005 --set solver.coarse_mesh_size=0.01 \
  --set postures.names=standing,supine
/usr/bin/python3 -c "
import json
for p in json.load(open('$work/mpi_coarse/summary.json'))['postures']:
    assert p['coarse_start'] and p['coarse_newton_iterations'] > 0, p"
# Nested grid sequencing (solver.nested_levels): a P2 case solved on the
# coarse P1 mesh, then on a P2 level at twice its mesh size (curved cells),
# every rank the whole ladder.
serial_vs_mpi nested --set geometry.mesh_size=0.01 --set geometry.order=2 \
  --set solver.coarse_mesh_size=0.02 --set postures.names=standing
/usr/bin/python3 -c "
import json
s = json.load(open('$work/mpi_nested/summary.json'))
assert [l['order'] for l in s['coarse_start']['levels']] == [1, 2], s['coarse_start']
for p in s['postures']:
    assert p['coarse_start'] and len(p['coarse_level_newton_iterations']) == 2, p"
# The AMG path (GMRES + GAMG, finest level smoothed by SOR: on 2 ranks a
# local symmetric sweep per rank, so the Krylov counts differ, not the result).
serial_vs_mpi amg --set solver.linear=amg --set postures.names=standing,supine
# The patient models of both example breasts (the fit's R and H rounded to
# 0.1 um, so both runs mesh the same caps): the same models.
for ranks in 1 2; do
  mpirun -n $ranks "$BIN" -q patient "$CASES/patient_example.json" --set geometry.mesh_size=0.012 --tolerance 4 \
    --out "$work/patient_$ranks" > /dev/null
done
/usr/bin/python3 - "$work/patient_1/patient_model.json" "$work/patient_2/patient_model.json" <<'PY'
import json, sys
a, b = (json.load(open(f))["sides"] for f in sys.argv[1:])
for x, y in zip(a, b, strict=True):
    assert x["R_m"] == y["R_m"] and x["H_m"] == y["H_m"], (x["side"], x["R_m"], y["R_m"], x["H_m"], y["H_m"])
    assert max(abs(p - q) for p, q in zip(x["nipple_standing_m"], y["nipple_standing_m"])) < 1e-9, x["side"]
    for k, v in x["achieved"].items():
        assert abs(v - y["achieved"][k]) < 1e-6, (x["side"], k, v, y["achieved"][k])
PY
echo "6 passed, 0 failed"
