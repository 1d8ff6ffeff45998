#!/usr/bin/env bash
# The 3D page of `breastsim view --compare` in headless Chromium (page_test.js).
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
NODE_PATH="$MODULES" node "$HERE/page_test.js" "$work/post/index.html"
