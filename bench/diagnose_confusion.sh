#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Missing-physics diagnosis on concealed data: for every hidden
# candidate (and the no-effect control) and every seed, a recording is made
# by `breastsim record` on a finer mesh, then `breastsim diagnose` names what
# it finds. Writes bench/results/diagnose/<hidden>_<seed>/ and a summary
# (confusion matrix, control false-discovery rate, recovery, time) printed
# and written to bench/results/diagnose/confusion.json.
#
# Usage: bash bench/diagnose_confusion.sh [BUILD_DIR] [SEEDS] [CASES]
#   SEEDS: number of seeds (default 3); CASES: space-separated subset of
#   "control base_springs skin suspensory_ligament gland_core".
#   FIRST_SEED (environment, default 1): seeds FIRST_SEED .. FIRST_SEED + SEEDS - 1.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
seeds="${2:-3}"
cases="${3:-control base_springs skin suspensory_ligament gland_core}"
out="${BENCH_OUT:-$here/results/diagnose}"
mkdir -p "$out"
bin="$build/breastsim"
case_file="$here/../cases/default.toml"

# The current model of each case: the candidate's own term is off.
current_sets() {
  case "$1" in
    skin) echo "--set terms.skin=false" ;;
    base_springs) echo "--set base.fixed=true --set terms.base_springs=false" ;;
    *) echo "" ;;
  esac
}

for hidden in $cases; do
  first="${FIRST_SEED:-1}"
  for seed in $(seq "$first" $((first + seeds - 1))); do
    dir="$out/${hidden}_${seed}"
    mkdir -p "$dir"
    sets=$(current_sets "$hidden")
    hide=""
    [ "$hidden" != control ] && hide="--hidden $hidden"
    # shellcheck disable=SC2086
    "$bin" -q record "$case_file" $sets $hide --seed "$seed" --mesh-size 0.004 \
      --out "$dir/recording.json"
    start=$(date +%s.%N)
    # shellcheck disable=SC2086
    "$bin" -q diagnose "$dir/recording.json" --case "$case_file" $sets --out "$dir/diagnosis" \
      > "$dir/diagnose.log" 2>&1 || { echo "diagnose failed: $dir"; cat "$dir/diagnose.log"; exit 1; }
    end=$(date +%s.%N)
    echo "$end - $start" | bc > "$dir/seconds"
    echo "$hidden seed $seed: $(grep -E '^(Missing|The)' "$dir/diagnose.log" | cut -c1-150)"
  done
done
/usr/bin/python3 "$here/diagnose_report.py" "$out" $cases
