#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Calibration with scans (docs/SCANS.md): synthetic patients with tissue.mu =
# 600 Pa (the default start is 400 Pa) scanned standing, supine and on all
# fours (3 holes, 0.5 mm noise, truth meshed at 6 mm); scan-calibrate fits
# FIT (default mu) from standing + supine and predicts all fours. Prints per
# patient the fitted values, their error against the truth, the 95 %
# intervals, the fitted and held-out RMS distances and the wall time.
# MESH_SIZE_M: scan-calibrate's --mesh-size (0: by the volume, as scan-model).
# Usage: bash bench/scan_calibrate.sh BUILD_DIR [MESH_SIZE_M] [FIT] [PATIENTS]
set -eu -o pipefail
BIN="$(cd "$1" && pwd)/breastsim"; H="${2:-0}"; FIT="${3:-mu}"; N="${4:-3}"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
i=0
for shape in "200 0.1 0.0 0.0" "400 0.3 0.1 0.15" "700 0.5 0.2 0.1" "1000 0.4 -0.1 0.3" "1500 0.6 0.15 0.2"; do
  set -- $shape; i=$((i + 1)); [ "$i" -le "$N" ] || break
  k=0
  for p in standing supine all_fours; do
    k=$((k + 1))
    "$BIN" -q synthetic-patient --volume "$1" --ptosis "$2" --lateral "$3" --asymmetry "$4" --mesh-size 0.006 \
      --noise 0.0005 --seed $((10 * i + k)) --set tissue.mu=600 --posture $p --out "p${i}_$p" >/dev/null
  done
  t0=$(date +%s.%N)
  "$BIN" -q scan-calibrate "p${i}_standing/scan.stl" --posture standing "p${i}_supine/scan.stl" --posture supine \
    --units mm --chest "p${i}_standing/chest.stl" --predict "p${i}_all_fours/scan.stl" --predict-posture all_fours \
    --mesh-size "$H" --fit "$FIT" --out "c$i" >/dev/null
  t1=$(date +%s.%N)
  echo "patient $i: volume $1 cm3, ptosis $2, lateral $3, asymmetry $4; scan-calibrate $(echo "$t1 - $t0" | bc) s"
  /usr/bin/python3 - "c$i/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
truth = {"tissue.mu": 600.0, "base.c": 200000.0}
for p in r["parameters"]:
    t = truth.get(p["key"])
    err = "" if t is None else " (truth %g, error %+.1f %%)" % (t, 100 * (p["value"] / t - 1))
    parts = "" if p["se_log_mesh"] is None else " (noise %.2f %%, mesh %.2f %%: %.6g on the coarser mesh)" % (
        100 * p["se_log_noise"], 100 * p["se_log_mesh"], p["value_coarse_mesh"])
    print("  %s = %.6g %s%s, SE %.2f %%%s, 95 %% interval [%.6g, %.6g]%s"
          % (p["name"], p["value"], p["unit"], err, p["relative_se_percent"], parts, p["interval95"][0],
             p["interval95"][1], "" if t is None or p["interval95"][0] <= t <= p["interval95"][1] else
             " (truth outside)"))
for key in ("scans_at_start", "scans_fitted", "scans_predicted"):
    for s in r[key]:
        print("  %-15s %-9s RMS %.3f mm (max %.3f mm, %d points off the chest)"
              % (key[6:], s["posture"], s["rms_mm"], s["max_mm"], s["points_used"]))
print("  tetrahedra %d, evaluations %d, reduced chi2 %.3f, fit %.1f s"
      % (r["inputs"]["tetrahedra"], r["evaluations"], r["reduced_chi2"], r["wall_time_s"]))
PY
done
