#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Wall time of the default case's `simulate` and `surgery` with and without
# pictures (output.pictures = none, the default, against full, which is what
# every run did before pictures became a separate step): medians of REPEATS
# runs of each, interleaved so that both see the same machine load, and the
# ratio full / none measured in the same run.
# Usage: bash bench/critical_path.sh [BREASTSIM] [REPEATS]   (defaults: build/breastsim 3)
set -euo pipefail
BIN="$(readlink -f "${1:-build/breastsim}")"; REPEATS="${2:-3}"
CASE="$(cd "$(dirname "$0")/.." && pwd)/cases/default.toml"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
wall() { local s e; s=$(date +%s.%N); "$@" >/dev/null; e=$(date +%s.%N); echo "$e - $s" | bc; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
for job in simulate surgery; do
  : > "$work/$job.none"; : > "$work/$job.full"
  for i in $(seq "$REPEATS"); do
    for mode in none full; do
      wall "$BIN" -q "$job" "$CASE" --set output.pictures=$mode --out "$job-$mode-$i" >> "$work/$job.$mode"
    done
  done
  none=$(median < "$work/$job.none"); full=$(median < "$work/$job.full")
  printf '%-9s pictures none %6.2f s   full %6.2f s   ratio full/none %.2f   (medians of %d; load %s)\n' \
    "$job" "$none" "$full" "$(echo "$full / $none" | bc -l)" "$REPEATS" "$(cut -d' ' -f1 /proc/loadavg)"
done
