#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Field discovery on a recording whose truth holds a stiff region no
# candidate has (docs/DISCOVERY.md): `breastsim record` of the default case
# with forms/tissue_field.py switched on (one Gaussian region, 4 x as stiff,
# width 12 mm, centre (25, 20, -30) mm; P2 truth at 6 mm, 3 postures x
# 2000 points, noise 0.5 mm), then `breastsim diagnose` with the field off.
# A demonstration on the project's own form: the out-of-sample test is the
# independent truth's "outside" set (bench/truth/README.md).
#
# Usage: bash bench/field_discovery_demo.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
out="${2:-$(mktemp -d /tmp/breastsim-field-demo.XXXXXX)}"
bin="$build/breastsim"
zeros() { printf ',0%.0s' $(seq 1 "$1"); }
amplitudes="1.3862943611198906$(zeros 23)"   # ln 4
centres="0.025,0.02,-0.03$(zeros 69)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$bin" -q record "$here/../cases/default.toml" --set terms.tissue_field=true \
  --set "tissue_field.amplitudes=$amplitudes" --set "tissue_field.centres=$centres" \
  --set tissue_field.width=0.012 --set geometry.order=2 --points 2000 --mesh-size 0.006 \
  --out "$out/recording.json"
mpirun -n 2 "$bin" -q diagnose "$out/recording.json" --case "$here/../cases/default.toml" \
  --fit mu,lambda --ranks-per-case 1 --out "$out/diagnosis" > "$out/diagnose.log"
sed -n '/^FIELD/,/^$/p' "$out/diagnosis/diagnosis.txt"
echo "results: $out"
