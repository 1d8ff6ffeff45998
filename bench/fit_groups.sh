#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Fits over MPI sub-communicators: the wall time of
#  - `calibrate` (default case, --fit mu,c,lambda --algorithm lbfgs: three
#    finite-difference Jacobian columns per gradient) and
#  - `diagnose` on independent-truth recordings of the benchmark (bench/truth)
#    (4 postures x 2000 points; the control control_01;
#    --fit mu,lambda: two columns, up to four candidate probes)
# on 1 rank and on 2 ranks with --ranks-per-case 1 (calibrate: each rank
# solves its own Jacobian columns, the other solves are replicated;
# diagnose: each rank solves its own postures of every evaluation).
# REPEATS times in turn (default 3); medians and the median of the ratios
# against the 1-rank run of the same repetition.
# Usage: bash bench/fit_groups.sh [BUILD_DIR] [REPEATS] [JOBS] [SET_DIR] [EXTRA]
#   JOBS: "calibrate" and recording names of SET_DIR (default
#   "calibrate control_01"), quoted; SET_DIR: a benchmark folder holding
#   recordings/ (default bench/truth); EXTRA: further diagnose arguments, quoted
#   (e.g. "--set terms.chest_wall=true --set geometry.rim_size_ratio=0.333").
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/.." && pwd)"
bin="$(cd "${1:-$repo/build}" && pwd)/breastsim"
repeats="${2:-3}"
jobs="${3:-calibrate control_01}"
set_dir="$(cd "${4:-$here/truth}" && pwd)"
read -r -a extra <<<"${5:-}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
"$bin" -q measure "$repo/cases/default.toml" --noise 0.0005 --seed 3 --out "$work/m.json" >/dev/null
printf '[tissue]\nmu = 300.0\n' >"$work/start.toml"
cal=(calibrate "$work/m.json" --case "$work/start.toml" --fit mu,c,lambda --algorithm lbfgs
     --max-evals 30 --size 320x240)
dia() { # RECORDING_NAME: the benchmark's diagnose arguments
  echo diagnose "$set_dir/recordings/$1.json" --case "$repo/cases/default.toml" \
    --set base.fixed=true --set terms.base_springs=false --set terms.skin=false --fit mu,lambda \
    "${extra[@]}"
}
timed() { # OUT_NAME COMMAND...: wall seconds; a failed run stops the benchmark
  local name="$1" t0 t1; shift
  t0=$(date +%s.%N)
  if ! "$@" --out "$work/$name" >"$work/$name.log" 2>&1; then
    echo "fit_groups.sh: failed: $*" >&2; tail -5 "$work/$name.log" >&2; exit 1
  fi
  t1=$(date +%s.%N)
  rm -rf "${work:?}/$name"
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.2f", b - a}'
}
: >"$work/times"
for i in $(seq 1 "$repeats"); do
  row=""
  for job in $jobs; do
    if [ "$job" = calibrate ]; then args=("${cal[@]}"); else read -r -a args <<<"$(dia "$job")"; fi
    s=$(timed "s_$job" "$bin" -q "${args[@]}") || exit 1
    g=$(timed "g_$job" mpirun -n 2 "$bin" -q "${args[@]}" --ranks-per-case 1) || exit 1
    echo "run $i, $job: 1 rank $s s; 2 ranks --ranks-per-case 1: $g s"
    row="$row $s $g"
  done
  echo "$row" >>"$work/times"
done
python3 - "$work/times" $jobs <<'PY'
import statistics, sys
rows = [list(map(float, l.split())) for l in open(sys.argv[1])]
names = {"calibrate": "calibrate mu,c,lambda"}
for k, job in enumerate(names.get(j, "diagnose " + j) for j in sys.argv[2:]):
    s = statistics.median(r[2 * k] for r in rows)
    g = statistics.median(r[2 * k + 1] for r in rows)
    ratio = statistics.median(r[2 * k] / r[2 * k + 1] for r in rows)
    print(f"{job}: medians over {len(rows)}: 1 rank {s:.1f} s; 2 ranks --ranks-per-case 1 {g:.1f} s "
          f"(speed-up {ratio:.2f})")
PY
