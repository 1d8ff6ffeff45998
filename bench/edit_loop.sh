#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# The edit loop of a researcher who edits UFL energies (docs/PERFORMANCE.md,
# "Edit loop"). In a scratch copy of this repository's committed sources
# (git worktree) with its own build, built once first (not timed):
#   edit: change an existing term (forms/skin.py) -> rebuild -> simulate
#   add:  a new term (bench/edit_loop/skin_pressure.py + one line in
#         forms/registry.py) -> rebuild -> simulate with the term on
# For each, the seconds of the rebuild (cmake --build --target breastsim,
# which re-runs CMake when forms/registry.py changed) and of the run of the
# default case, and the objects the rebuild compiled. Each loop is repeated
# REPEATS times (the edit undone in between, undo not timed); medians.
#
# Usage: bash bench/edit_loop.sh [REPEATS] [SCRATCH_DIR]
#   REPEATS default 3; SCRATCH_DIR default a new mktemp folder (removed at
#   the end unless KEEP_SCRATCH=1). BUILD=DIR: instead of a scratch copy,
#   edit this checkout in place with its existing build DIR (the edits are
#   undone at the end, also on failure; the tree must be clean in forms/). CHECK=1: also fail (exit 1) unless the
#   add loop compiled only the new term's kernels and the registry, the new
#   keys are listed by `breastsim keys`, and the pressure moves the nipple.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/.." && pwd)"
repeats="${1:-3}"
scratch="${2:-$(mktemp -d /tmp/breastsim-edit-loop.XXXXXX)}"
out="$scratch/results"
if [ -n "${BUILD:-}" ]; then
  src="$repo"
  build="$(cd "$BUILD" && pwd)"
  git -C "$repo" diff --quiet -- forms || { echo "edit loop: forms/ has uncommitted changes"; exit 2; }
  cleanup() { git -C "$repo" checkout -- forms/skin.py forms/registry.py
              rm -f "$repo/forms/skin_pressure.py"
              cmake --build "$build" -j "$(nproc)" --target breastsim >/dev/null 2>&1 || true
              [ "${KEEP_SCRATCH:-0}" = 1 ] || rm -rf "$scratch"; }
  trap cleanup EXIT
  echo "edit loop: in place, build $build; bringing it up to date (not timed) ..."
else
  src="$scratch/src"
  build="$scratch/build"
  cleanup() { git -C "$repo" worktree remove --force "$src" >/dev/null 2>&1 || true
              [ "${KEEP_SCRATCH:-0}" = 1 ] || rm -rf "$scratch"; }
  trap cleanup EXIT
  git -C "$repo" worktree add --detach "$src" HEAD >/dev/null
  echo "edit loop: scratch $scratch; initial build (not timed) ..."
  cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
fi
cmake --build "$build" -j "$(nproc)" --target breastsim >/dev/null

# rebuild LOG: time the incremental build of breastsim, log what it compiled.
rebuild() {
  local t0 t1
  t0=$(date +%s.%N)
  cmake --build "$build" -j "$(nproc)" --target breastsim >"$1" 2>&1
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.1f\n", b - a}'
}
# run NAME [--set ...]: time the default case, write into a fresh folder.
run() {
  local name="$1" t0 t1
  shift
  rm -rf "$out/$name"
  mkdir -p "$out"
  t0=$(date +%s.%N)
  "$build/breastsim" simulate "$src/cases/default.toml" --out "$out/$name" "$@" >"$out/$name.log" 2>&1
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.1f\n", b - a}'
}
compiled() { grep -oE 'Building (C|CXX) object [^ ]+' "$1" | awk '{print $4}' | xargs -n1 basename | sort | tr '\n' ' '; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

edit_b=() edit_r=() add_b=() add_r=()
for i in $(seq 1 "$repeats"); do
  # Edit an existing term: the skin law gains a (zero) extra contribution.
  cp "$src/forms/skin.py" "$scratch/skin.py.orig"
  echo "ENERGY = ENERGY + 0 * t_s * W_s * ds(\"skin\", \"surface\")  # edit-loop probe $i" >>"$src/forms/skin.py"
  edit_b+=("$(rebuild "$scratch/edit_$i.log")")
  edit_r+=("$(run "edit_$i")")
  echo "edit $i: rebuild ${edit_b[-1]} s (compiled: $(compiled "$scratch/edit_$i.log")), run ${edit_r[-1]} s"
  cp "$scratch/skin.py.orig" "$src/forms/skin.py"
  rebuild "$scratch/edit_undo_$i.log" >/dev/null

  # Add a new term: one UFL file and one registration line.
  cp "$here/edit_loop/skin_pressure.py" "$src/forms/skin_pressure.py"
  cp "$src/forms/registry.py" "$scratch/registry.py.orig"
  sed -i 's/^TERMS = \[/TERMS = [\n    "skin_pressure",/' "$src/forms/registry.py"
  add_b+=("$(rebuild "$scratch/add_$i.log")")
  add_r+=("$(run "add_$i" --set terms.skin_pressure=true --set skin_pressure.p=50)")
  echo "add $i: rebuild ${add_b[-1]} s (compiled: $(compiled "$scratch/add_$i.log")), run ${add_r[-1]} s"
  if [ "${CHECK:-0}" = 1 ] && [ "$i" = 1 ]; then
    got="$(compiled "$scratch/add_1.log")"
    want="breastsim_registry.cpp.o term_skin_pressure_p1.c.o term_skin_pressure_p2.c.o "
    [ "$got" = "$want" ] || { echo "FAIL: the add loop compiled '$got', expected '$want'"; exit 1; }
    "$build/breastsim" keys | grep -q "skin_pressure.p" || { echo "FAIL: keys lacks skin_pressure.p"; exit 1; }
    run add_off >/dev/null
    python3 - "$out/add_1/summary.json" "$out/add_off/summary.json" <<'PY' || exit 1
import json, sys
on, off = (json.load(open(p))["postures"][0]["nipple_m"] for p in sys.argv[1:3])
d = max(abs(a - b) for a, b in zip(on, off))
print(f"nipple moved by {1e3 * d:.3f} mm with the 50 Pa skin pressure")
sys.exit(0 if d > 1e-5 else 1)
PY
  fi
  rm "$src/forms/skin_pressure.py"
  cp "$scratch/registry.py.orig" "$src/forms/registry.py"
  rebuild "$scratch/add_undo_$i.log" >/dev/null
done

echo "edit loop, medians over $repeats: edit term: rebuild $(printf '%s\n' "${edit_b[@]}" | median) s," \
     "run $(printf '%s\n' "${edit_r[@]}" | median) s; add term: rebuild" \
     "$(printf '%s\n' "${add_b[@]}" | median) s, run $(printf '%s\n' "${add_r[@]}" | median) s"
