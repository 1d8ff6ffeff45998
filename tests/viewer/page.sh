#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# The 3D page of `breastsim view --compare` in headless Chromium (page_test.js):
# the half cap drawn with its mirror image, and a full breast (a synthetic
# patient's scan through scan-model, simulated, then `view`) drawn as it is.
# Usage: page.sh BREASTSIM CASES_DIR NODE_MODULES_DIR
set -eu
BIN="$1"; CASES="$2"; MODULES="$3"; HERE="$(cd "$(dirname "$0")" && pwd)"
[ -x /usr/bin/chromium ] || { echo "Debian's chromium is missing: run bash .ci/setup"; exit 1; }
[ -d "$MODULES/playwright-core" ] || { echo "playwright-core missing in $MODULES: run bash .ci/setup"; exit 1; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
"$BIN" -q simulate "$CASES/default.toml" --set geometry.mesh_size=0.012 --out "$work/pre"
"$BIN" -q simulate "$CASES/default.toml" --set geometry.mesh_size=0.012 --set tissue.mu=1600 \
  --out "$work/post"
"$BIN" -q view "$work/post" --compare "$work/pre" --size 400x300 >/dev/null
NODE_PATH="$MODULES" node "$HERE/page_test.js" "$work/post/index.html" half
"$BIN" -q synthetic-patient --volume 400 --ptosis 0.3 --lateral 0.1 --asymmetry 0.15 --mesh-size 0.01 \
  --out "$work/patient" >/dev/null
"$BIN" -q scan-model "$work/patient/scan.stl" --units mm --posture standing --mesh-size 0.012 \
  --out "$work/scan" >/dev/null
"$BIN" -q simulate "$work/scan/case.toml" --set postures.names=standing,supine --set output.xdmf=false \
  --out "$work/full" >/dev/null
"$BIN" -q view "$work/full" --size 400x300 >/dev/null
NODE_PATH="$MODULES" node "$HERE/page_test.js" "$work/full/index.html" full
