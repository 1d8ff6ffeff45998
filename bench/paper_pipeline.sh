#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# The paper's whole pipeline, wall time: calibrate the stiffnesses from the
# example measurements (cases/measurements_example.json), then the surgery
# of the calibrated case (calibrated.toml: the default incision, three
# post-operative postures: standing, supine, on all fours), no pictures.
# Medians of REPEATS runs of each step and of the sum.
# Usage: bash bench/paper_pipeline.sh [BREASTSIM] [REPEATS]   (defaults: build/breastsim 3)
set -euo pipefail
BIN="$(readlink -f "${1:-build/breastsim}")"; REPEATS="${2:-3}"
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
wall() { local s e; s=$(date +%s.%N); "$@" >/dev/null; e=$(date +%s.%N); echo "$e - $s" | bc; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
: > calibrate; : > surgery; : > total
for i in $(seq "$REPEATS"); do
  c=$(wall "$BIN" -q calibrate "$ROOT/cases/measurements_example.json" --out cal-$i)
  s=$(wall "$BIN" -q surgery cal-$i/calibrated.toml --out surgery-$i)
  echo "$c" >> calibrate; echo "$s" >> surgery; echo "$c + $s" | bc >> total
done
printf 'calibrate %.2f s, surgery %.2f s, pipeline %.2f s (medians of %d; load %s)\n' \
  "$(median < calibrate)" "$(median < surgery)" "$(median < total)" "$REPEATS" "$(cut -d' ' -f1 /proc/loadavg)"
