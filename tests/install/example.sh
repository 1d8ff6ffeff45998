#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# `cmake --install` into a scratch prefix; examples/ builds against the
# installed package and runs (its standing nipple equals the CLI's); the
# installed program finds its assets beside it (a simulate with pictures).
# Usage: example.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
BUILD="$(readlink -f "$1")"; SRC="$(readlink -f "$2")"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cmake --install "$BUILD" --prefix "$work/prefix" > "$work/install.log"
test -x "$work/prefix/bin/breastsim"
test -f "$work/prefix/include/breastsim/model.hpp"
test -f "$work/prefix/lib/cmake/breastsim/breastsimConfig.cmake"
cmake -S "$SRC/examples" -B "$work/example" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/example" -j 2 > "$work/build.log"
cd "$work"
"$work/example/standing_nipple" | tee example.out
"$work/prefix/bin/breastsim" -q simulate "$SRC/cases/default.toml" --set geometry.mesh_size=0.012 \
  --set postures.names=standing --set output.pictures=full --out cli > cli.out
python3 - <<'PY'
import json, re
ex = [float(v) for v in re.findall(r"-?\d+\.\d+", open("example.out").read())]
cli = [1e3 * v for v in json.load(open("cli/summary.json"))["postures"][0]["nipple_m"]]
assert len(ex) == 3 and max(abs(a - b) for a, b in zip(ex, cli)) < 0.01, (ex, cli)
print("the example's nipple equals the CLI's:", ex)
PY
test -s cli/view_standing.png # the installed picture scripts were found
"$work/prefix/bin/breastsim" -q view cli > /dev/null
grep -q "OrbitControls" cli/index.html # ... and the 3D page's three.js
echo "installed package, example and assets: ok"
