#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Time of the scan pipeline ("scan to neutral state to three
# postures takes <= 60 s at default resolution"): a synthetic patient's scan
# (SHAPE: volume cm3, ptosis, lateral, asymmetry; 0.5 mm noise, 3 holes, the
# truth meshed at 6 mm) goes scan-model (default mesh size, P1, chest plane
# fitted through the footprint; with CHEST = chest the true chest wall is
# given) -> neutral-state (standing) -> simulate of standing, supine and
# all fours, every output at its default. Each stage is timed in wall
# seconds, REPEATS times; prints the median per stage and of the totals and
# exits 1 when the median total is above LIMIT_S (60).
# Usage: bash bench/scan_pipeline.sh [BUILD_DIR] [REPEATS] [CHEST] [SHAPE] [LIMIT_S]
#   e.g. nice -n 10 bash bench/scan_pipeline.sh build 3
set -eu -o pipefail
BUILD="${1:-build}"; REPEATS="${2:-3}"; CHEST="${3:-}"; SHAPE="${4:-700 0.5 0.2 0.1}"; LIMIT="${5:-60}"
BIN="$(cd "$BUILD" && pwd)/breastsim"
[ -x "$BIN" ] || { echo "no breastsim in $BUILD"; exit 2; }
[ "$REPEATS" -ge 1 ] 2>/dev/null || { echo "REPEATS must be a positive integer (got '$REPEATS')"; exit 2; }
case "$CHEST" in ""|footprint|chest) ;; *) echo "CHEST must be 'chest' or 'footprint' (got '$CHEST')"; exit 2;; esac
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
set -- $SHAPE
"$BIN" -q synthetic-patient --volume "$1" --ptosis "$2" --lateral "$3" --asymmetry "$4" --mesh-size 0.006 \
  --noise 0.0005 --holes 3 --seed 3 --posture standing --out patient >/dev/null
echo "synthetic patient: volume $1 cm3, ptosis $2, lateral $3, asymmetry $4 (0.5 mm noise, 3 holes)"
chest=()
[ "$CHEST" = chest ] && chest=(--chest patient/chest.stl)

now() { date +%s.%N; }
for r in $(seq 1 "$REPEATS"); do
  rm -rf model neutral postures
  t0=$(now)
  "$BIN" -q scan-model patient/scan.stl --units mm --posture standing "${chest[@]}" --out model >/dev/null
  t1=$(now)
  "$BIN" -q neutral-state model/case.toml --posture standing --out neutral >/dev/null
  t2=$(now)
  "$BIN" -q simulate neutral/case.reference.toml --set postures.names=standing,supine,all_fours \
    --out postures >/dev/null
  t3=$(now)
  line=$(echo "$t1 - $t0; $t2 - $t1; $t3 - $t2; $t3 - $t0" | bc | tr '\n' ' ')
  echo "run $r: scan-model, neutral-state, three postures, total [s]: $line"
  echo "$line" >>times.txt
done
tets=$(/usr/bin/python3 -c "import json; print(json.load(open('model/summary.json'))['tetrahedra'])")
/usr/bin/python3 - times.txt "$LIMIT" "$tets" "$REPEATS" <<'PY'
import statistics, sys
limit, tets, n = float(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
rows = [list(map(float, l.split())) for l in open(sys.argv[1]) if l.strip()]
names = ["scan-model", "neutral-state", "three postures", "total"]
med = [statistics.median(r[k] for r in rows) for k in range(4)]
print(f"tetrahedra {tets}; medians of {n} runs:")
for name, m in zip(names, med):
    print(f"  {name:15s} {m:7.2f} s")
ok = med[3] <= limit
print(f"scan to neutral state to three postures: {med[3]:.2f} s median "
      f"({'within' if ok else 'ABOVE'} the {limit:g} s goal)")
sys.exit(0 if ok else 1)
PY
