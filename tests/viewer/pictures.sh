#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Pictures of `simulate` and `view`: produced, non-empty, of the requested
# size; standing differs from supine; pre vs post differ; a missing
# python3/matplotlib is a clear error that leaves no output.
# Usage: pictures.sh BREASTSIM CASES_DIR
set -eu
BIN="$1"; CASES="$2"; HERE="$(cd "$(dirname "$0")" && pwd)"
CHECK="/usr/bin/python3 $HERE/png_check.py"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
passed=0

# 1. simulate with output.pictures = full writes the default-size pictures
#    next to summary.json; by default (none) it writes no picture at all.
"$BIN" -q simulate "$CASES/default.toml" --set postures.names=standing --out "$work/plain"
! ls "$work/plain" | grep -q '\.png$\|index.html'
"$BIN" -q simulate "$CASES/default.toml" --set output.pictures=full --out "$work/pre"
for p in standing supine all_fours; do
  test -s "$work/pre/surface_$p.json"
  $CHECK size "$work/pre/view_$p.png" 800 600
  $CHECK drawn "$work/pre/view_$p.png"
done
$CHECK size "$work/pre/overview.png" 800 600
$CHECK differ "$work/pre/view_standing.png" "$work/pre/view_supine.png"
passed=$((passed + 1))

# 2. view --compare --size: pre vs post (a stiffer breast stands for "post").
"$BIN" -q simulate "$CASES/default.toml" --set tissue.mu=1600 --set postures.names=standing \
  --out "$work/post"
"$BIN" -q view "$work/post" --compare "$work/pre" --size 640x480 > "$work/view.out"
grep -q "file://.*/post/index.html" "$work/view.out"
$CHECK size "$work/post/view_standing.png" 640 480
$CHECK size "$work/post/compare_standing.png" 640 480
test ! -e "$work/post/compare_supine.png"   # posture missing in post: no comparison
"$BIN" -q view "$work/pre" --size 640x480 >/dev/null
$CHECK differ "$work/pre/view_standing.png" "$work/post/view_standing.png"
test -s "$work/post/index.html"
passed=$((passed + 1))

# 3. bad size: input error (exit 2) naming the option.
set +e
"$BIN" -q view "$work/pre" --size 12x7 2> "$work/err"; code=$?
set -e
[ "$code" -eq 2 ] || { echo "bad --size: exit $code, expected 2"; exit 1; }
grep -q -- "--size" "$work/err"
passed=$((passed + 1))

# 4. no python3/matplotlib: clear message, no output folder.
set +e
BREASTSIM_PYTHON=/nonexistent/python3 "$BIN" -q simulate "$CASES/default.toml" --set output.pictures=full --out "$work/none" \
  2> "$work/err"; code=$?
set -e
[ "$code" -ne 0 ] || { echo "simulate without python3 succeeded"; exit 1; }
grep -q "python3-matplotlib" "$work/err" || { cat "$work/err"; exit 1; }
test ! -e "$work/none"
passed=$((passed + 1))

# 5. a surgery result: `view` draws pre-op, post-op against pre-op and the page in postop/.
"$BIN" -q surgery "$CASES/default.toml" --set geometry.mesh_size=0.012 --set postures.names=standing \
  --out "$work/surgery"
! find "$work/surgery" -name '*.png' | grep -q .
"$BIN" -q view "$work/surgery" --size 400x300 > "$work/view_surgery.out"
grep -q "file://.*/surgery/postop/index.html" "$work/view_surgery.out"
$CHECK size "$work/surgery/preop/view_standing.png" 400 300
$CHECK size "$work/surgery/postop/compare_standing.png" 400 300
test -s "$work/surgery/postop/index.html"
passed=$((passed + 1))

echo "$passed passed, 0 failed"
