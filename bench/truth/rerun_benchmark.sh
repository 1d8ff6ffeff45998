#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# The whole independent-truth benchmark again with one binary: every set of
# benchmark_runs.json diagnosed with run_diagnose.py (the commands of
# docs/DIAGNOSE.md; a recording with a result in RESULTS is skipped, so an
# interrupted run resumes), then scored together by rescore.py --benchmark
# into RESULTS/pooled.json, to set beside measured/pooled.json. Each set's
# results go to RESULTS/<set folder with / as ->, e.g. chest_wall-validation.
# Usage: bash bench/truth/rerun_benchmark.sh BUILD_DIR RESULTS_DIR
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: bash bench/truth/rerun_benchmark.sh BUILD_DIR RESULTS_DIR" >&2; exit 2; }
TRUTH="$(cd "$(dirname "$0")" && pwd)"
BUILD="$(readlink -f "$1")"
mkdir -p "$2"; RES="$(readlink -f "$2")"
EXTRA="--set terms.chest_wall=true --set geometry.rim_size_ratio=0.333"
sets=$(python3 -c "import json, sys; print(' '.join(json.load(open(sys.argv[1]))['runs']))" "$TRUTH/benchmark_runs.json")
for s in $sets; do
  extra="$EXTRA"
  # The committed glandform run left out the gland's lobe form and the
  # skin's upper-pole variation (benchmark_runs.json, "about").
  [ "$s" != chest_wall/glandform ] ||
    extra="$EXTRA --candidates skin,base_springs,suspensory_ligament,suspensory_cables,gland_core"
  python3 "$TRUTH/run_diagnose.py" "$BUILD" --manifest "$TRUTH/$s/manifest.json" --out "$RES/${s//\//-}" \
    --jobs 1 --mpi 2 --ranks-per-case 1 --extra "$extra"
done
python3 - "$TRUTH/benchmark_runs.json" "$RES" > "$RES/benchmark_runs.json" <<'PY'
import json, sys
spec = json.load(open(sys.argv[1]))
spec["about"] = f"every set diagnosed again into {sys.argv[2]} (bench/truth/rerun_benchmark.sh)"
spec["runs"] = {s: f"{sys.argv[2]}/{s.replace('/', '-')}/summary.json" for s in spec["runs"]}
print(json.dumps(spec, indent=1))
PY
python3 "$TRUTH/rescore.py" --benchmark "$RES/benchmark_runs.json" --out "$RES/pooled.json"
