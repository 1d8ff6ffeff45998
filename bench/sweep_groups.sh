#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# The paper's Fig. 10 sweep (README, "Surgery and incision sweeps": a = 25,
# 30, 35 deg x h = 20, 30 mm, standing, the default 8 mm P1 mesh) on 1 rank,
# on 2 ranks solving each surgery together (--ranks-per-case 0, the default)
# and on 2 ranks each solving its own surgeries (--ranks-per-case 1, MPI
# sub-communicators). Wall time of each, REPEATS times in turn (default 3);
# medians and ratios against the 1-rank run of the same repetition.
# Usage: bash bench/sweep_groups.sh [BUILD_DIR] [REPEATS]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/.." && pwd)"
bin="$(cd "${1:-$repo/build}" && pwd)/breastsim"
repeats="${2:-3}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
args=(sweep "$repo/cases/default.toml" --vary a=25,30,35 --vary h=0.02,0.03 --set postures.names=standing)
timed() { # OUT_NAME COMMAND...: wall seconds
  local name="$1" t0 t1; shift
  t0=$(date +%s.%N); "$@" --out "$work/$name" >"$work/$name.log" 2>&1; t1=$(date +%s.%N)
  rm -rf "${work:?}/$name"
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.2f", b - a}'
}
: >"$work/times"
for i in $(seq 1 "$repeats"); do
  s=$(timed serial "$bin" -q "${args[@]}")
  a=$(timed all mpirun -n 2 "$bin" -q "${args[@]}" --ranks-per-case 0)
  g=$(timed groups mpirun -n 2 "$bin" -q "${args[@]}" --ranks-per-case 1)
  echo "run $i: 1 rank $s s; 2 ranks, each surgery on both: $a s; 2 ranks, one surgery each: $g s"
  echo "$s $a $g" >>"$work/times"
done
python3 - "$work/times" <<'PY'
import statistics, sys
rows = [list(map(float, l.split())) for l in open(sys.argv[1])]
med = [statistics.median(c) for c in zip(*rows)]
ratios = [statistics.median(r[0] / r[k] for r in rows) for k in (1, 2)]
print(f"medians over {len(rows)}: 1 rank {med[0]:.1f} s; 2 ranks --ranks-per-case 0 {med[1]:.1f} s "
      f"(speed-up {ratios[0]:.2f}); 2 ranks --ranks-per-case 1 {med[2]:.1f} s (speed-up {ratios[1]:.2f})")
PY
