#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Benchmarks of one standing posture solve (not tests): wall time and peak
# memory for meshes of about 5k, 50k and 200k tetrahedra, P1 and P2, direct
# (MUMPS) and AMG (GMRES + GAMG), serial and 2 MPI ranks. Every configuration
# runs REPEATS times; the median is reported. Results: bench/results.json and
# the table in docs/PERFORMANCE.md (written by bench/report.py).
#
# Usage: bash bench/run_benchmarks.sh [BUILD_DIR] [REPEATS] [FILTER]
#   FILTER: a regular expression on the configuration label, e.g. 'P1' or '50k'.
#   TIMEOUT (environment, seconds, default 600): a run longer than this is
#   stopped and recorded as a timeout (the remaining repeats are skipped).
#   VARIANT and EXTRA (environment): a label suffix and extra --set options,
#   for a baseline in the same run, e.g.
#   VARIANT=_nocoarse EXTRA="--set solver.coarse_start=false".
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}; REPEATS=${2:-3}; FILTER=${3:-.}
BIN="$BUILD/breastsim"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
out=bench/results.jsonl
[ "${APPEND:-0}" = 1 ] || : > "$out"   # APPEND=1 adds to an earlier run

# mesh_size giving ~5k / ~50k / ~200k tetrahedra for the default cap.
declare -A H=( [5k]=0.0075 [50k]=0.003 [200k]=0.0019 )
for size in 5k 50k 200k; do
  for order in 1 2; do
    for linear in direct amg; do
      for ranks in 1 2; do
        label="${size}_P${order}_${linear}_np${ranks}${VARIANT:-}"
        [[ "$label" =~ $FILTER ]] || continue
        # MUMPS on P2 beyond the 5k mesh (230k+ unknowns, dense 30x30 element
        # couplings) is far slower than AMG: only AMG runs for the larger P2 meshes.
        if [ "$linear" = direct ] && [ "$order" = 2 ] && [ "$size" != 5k ]; then continue; fi
        for rep in $(seq "$REPEATS"); do
          cmd=("$BIN" -q simulate cases/default.toml --set postures.names=standing
               --set geometry.mesh_size=${H[$size]} --set geometry.order=$order
               --set solver.linear=$linear --set output.xdmf=false ${EXTRA:-} --out "$work/$label")
          [ "$ranks" = 2 ] && cmd=(mpirun -n 2 "${cmd[@]}")
          rc=0
          timeout "${TIMEOUT:-600}" /usr/bin/time -f "%e %M" -o "$work/time" "${cmd[@]}" > /dev/null 2> "$work/err" || rc=$?
          if [ "$rc" = 124 ]; then
            echo "{\"label\": \"$label\", \"failed\": true, \"timeout_s\": ${TIMEOUT:-600}}" >> "$out"
            echo "$label: timeout after ${TIMEOUT:-600} s"; break
          elif [ "$rc" != 0 ]; then
            echo "{\"label\": \"$label\", \"failed\": true}" >> "$out"; cat "$work/err"; break
          fi
          read -r wall rss < "$work/time"
          /usr/bin/python3 - "$label" "$wall" "$rss" "$ranks" "${cmd[*]}" "$work/$label/summary.json" >> "$out" <<'PY'
import json, sys
label, wall, rss, ranks, cmd, summary = sys.argv[1:]
s = json.load(open(summary))
p = s["postures"][0]
# The solve includes the coarse start's set-up (the meshes and models of its
# levels, node location); the levels' solves are inside the posture's wall time.
coarse = s.get("coarse_start", {})
print(json.dumps({"label": label, "cells": s["mesh"]["cells"], "order": s["mesh"]["order"],
                  "unknowns": s["unknowns"], "linear": s["linear_solver"], "ranks": int(ranks),
                  "solve_s": p["wall_time_s"] + coarse.get("setup_s", 0.0),
                  "coarse_unknowns": coarse.get("unknowns", 0),
                  "coarse_newton": p.get("coarse_newton_iterations", 0),
                  "level_unknowns": [l["unknowns"] for l in coarse.get("levels", [])],
                  "level_newton": p.get("coarse_level_newton_iterations", []),
                  "process_wall_s": float(wall),
                  "peak_rss_MB_rank0": int(rss) / 1024, "newton": p["newton_iterations"],
                  "krylov": p["linear_iterations"], "command": cmd}))
PY
          echo "$label rep $rep: $(tail -1 "$out" | cut -c1-160)"
        done
      done
    done
  done
done
/usr/bin/python3 bench/report.py "$out" docs/PERFORMANCE.md
