#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Wall time of `calibrate` on cases/measurements_example.json and of
# `diagnose` on benchmark recordings, for a baseline binary (OLD, e.g. one
# built from an earlier commit) and this one (NEW), each with its own
# defaults, interleaved so that both see the same machine load: medians of
# REPEATS runs, the ratio OLD / NEW from the same run, and the results
# compared (calibrate: fitted values; diagnose: the terms named and the
# fitted values).
# Usage: bash bench/fit_speed.sh OLD NEW [REPEATS] [RECORDING...]
#   (default REPEATS 3; RECORDING: names in bench/truth/manifest.json, default
#   control_01 skin_weak_2, the ctest truth_diagnose's pair; "none": calibrate only)
set -euo pipefail
OLD="$(readlink -f "$1")"; NEW="$(readlink -f "$2")"; REPEATS="${3:-3}"; shift $(( $# < 3 ? $# : 3 ))
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
RECS=("$@")
[ ${#RECS[@]} -gt 0 ] || RECS=(control_01 skin_weak_2)
[ "${RECS[0]}" != none ] || RECS=()
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
wall() { local s e; s=$(date +%s.%N); "$@" >/dev/null 2>&1; e=$(date +%s.%N); echo "$e - $s" | bc; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
report() { # NAME: medians, ratio
  local old new; old=$(median < "$1.old"); new=$(median < "$1.new")
  printf '%-28s old %7.2f s   new %7.2f s   old/new %.2f   (medians of %d; load %s)\n' \
    "$1" "$old" "$new" "$(echo "$old / $new" | bc -l)" "$REPEATS" "$(cut -d' ' -f1 /proc/loadavg)"
}

: > calibrate.old; : > calibrate.new
for i in $(seq "$REPEATS"); do
  wall "$OLD" -q calibrate "$ROOT/cases/measurements_example.json" --out cal-old-$i >> calibrate.old
  wall "$NEW" -q calibrate "$ROOT/cases/measurements_example.json" --out cal-new-$i >> calibrate.new
done
report calibrate
python3 - cal-old-1/report.json cal-new-1/report.json <<'PY'
import json, sys
old, new = (json.load(open(f)) for f in sys.argv[1:3])
def values(r): return {p["name"]: p["fitted"] for p in r["fit"]}
for k, v in values(old).items():
    w = values(new)[k]
    print(f"  {k}: old {v:.6g}, new {w:.6g}, relative difference {abs(w - v) / abs(v):.1e}")
print(f"  evaluations: old {old['evaluations']}, new {new['evaluations']}")
PY

[ ${#RECS[@]} -gt 0 ] || exit 0
# diagnose: bench/truth/run_diagnose.py (the benchmark's own options) with each binary in turn.
names=$(IFS=,; echo "${RECS[*]}")
for i in $(seq "$REPEATS"); do
  for which in old new; do
    bin=$([ $which = old ] && echo "$OLD" || echo "$NEW")
    mkdir -p "bin-$which"; ln -sf "$bin" "bin-$which/breastsim"
    python3 "$ROOT/bench/truth/run_diagnose.py" "bin-$which" --only "$names" --rerun --nice -1 \
      --out "d-$which-$i" >/dev/null 2>&1
  done
done
python3 - "$REPEATS" <<'PY'
import json, statistics, sys
n = int(sys.argv[1])
runs = {w: [{r["name"]: r for r in json.load(open(f"d-{w}-{i}/summary.json"))["rows"]} for i in range(1, n + 1)]
        for w in ("old", "new")}
for name in runs["old"][0]:
    t = {w: statistics.median(r[name]["seconds"] for r in runs[w]) for w in runs}
    each = {w: " ".join(f"{r[name]['seconds']:.1f}" for r in runs[w]) for w in runs}
    print(f"diagnose {name:<19} old {t['old']:7.1f} s   new {t['new']:7.1f} s   old/new {t['old'] / t['new']:.2f}"
          f"   (medians of {n}: old {each['old']}, new {each['new']})")
    for w in ("old", "new"):
        r = runs[w][0][name]
        if r.get("exit_code"):
            print(f"  {w}: failed (exit code {r['exit_code']})")
            continue
        print(f"  {w}: named {r['named'] or 'none'}, fitted " +
              ", ".join(f"{k} = {v:.5g}" for k, v in r.get("fitted", {}).items()))
PY
