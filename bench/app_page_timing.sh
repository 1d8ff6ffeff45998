#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# The planning app's two speed targets, measured by the browser
# test and asserted here: the page's first view < 1 s (median of 5 loads)
# and a slider move redrawing the planes < 100 ms (median of 9 moves), from
# the page's User Timing marks. Runs the whole browser walk once
# (tests/app/page.sh) with BREASTSIM_TIMING_TARGETS=1; prints timings.json.
# Run it on a machine that is not busy with other work.
# Usage: bash bench/app_page_timing.sh [BUILD_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/.." && pwd)"
build="$(cd "${1:-$repo/build}" && pwd)"
shots=$(mktemp -d); trap 'rm -rf "$shots"' EXIT
BREASTSIM_TIMING_TARGETS=1 bash "$repo/tests/app/page.sh" "$build/breastsim" "$repo/cases" \
  "$repo/src/viewer/web/node_modules" "$shots" | grep -E "first view|slider move|checks? passed|passed"
cat "$shots/timings.json"
