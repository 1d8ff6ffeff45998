#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# `breastsim serve` end to end, in one scratch folder, on a free loopback port:
# refused options and data folders; hostile requests (malformed JSON, unknown
# keys, out-of-range values, oversized bodies, path traversal, CORS, foreign
# Host); the planning checks; a patient job equal to the CLI's `patient` and
# refused patient and plan requests; a surgery job whose numbers equal the CLI's
# `breastsim surgery` on the same keys; a calibration equal to `calibrate`'s,
# its evaluations (the progress channel, live and final) equal to its report's;
# a surgery on an uploaded scan's breast equal to the CLI's on the scan's neutral case;
# a failing solve and a killed job process (the server stays up); cancelling a queued and a running job
# (nothing of them left); a restart that finds the finished job again; two
# jobs at once with --workers 2.
set -eu
BIN="$1"; HERE="$(cd "$(dirname "$0")" && pwd)"; CASES="${2:-$HERE/../../cases}"
work=$(mktemp -d)
server_pid=""
stop_server() { if [ -n "$server_pid" ]; then kill "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true; server_pid=""; fi; }
trap 'stop_server; rm -rf "$work"' EXIT
checks() { /usr/bin/python3 "$HERE/server_checks.py" "$port" "$@"; }

starts=0
start_server() {   # a new output file each time: the port is never read from an earlier server's
  starts=$((starts + 1)); out="$work/serve-$starts.out"
  "$BIN" serve --port 0 --data "$work/data" "$@" > "$out" 2>&1 &
  server_pid=$!
  for _ in $(seq 1 100); do
    port=$(grep -o 'listening on http://127.0.0.1:[0-9]*' "$out" 2>/dev/null | grep -o '[0-9]*$' || true)
    [ -n "$port" ] && return 0
    kill -0 "$server_pid" 2>/dev/null || { cat "$out"; return 1; }
    sleep 0.1
  done
  echo "server did not start"; cat "$out"; return 1
}

# Options and data folders refused before listening (exit code 2, message naming them).
mkdir "$work/notes"; echo "mine" > "$work/notes/keep.txt"
set +e
"$BIN" serve --port 0 --data "$work/notes" > "$work/refused.txt" 2>&1; rc1=$?
"$BIN" serve --port 0 --workers 0 --data "$work/d2" >> "$work/refused.txt" 2>&1; rc2=$?
"$BIN" serve --port 70000 --data "$work/d3" >> "$work/refused.txt" 2>&1; rc3=$?
"$BIN" serve --run-job "$work/notes" >> "$work/refused.txt" 2>&1; rc4=$?   # the job process's entry
set -e
cat "$work/refused.txt"
[ $rc1 = 2 ] && [ $rc2 = 2 ] && [ $rc3 = 2 ] && [ $rc4 = 2 ]
grep -q "notes: not a job folder of breastsim serve" "$work/refused.txt"
grep -q "notes: refused: it is not empty and was not created by breastsim serve" "$work/refused.txt"
grep -q -- "--workers = 0 is out of range: allowed \[1, 16\]" "$work/refused.txt"
[ "$(cat "$work/notes/keep.txt")" = mine ] && [ "$(ls -A "$work/notes")" = keep.txt ]

start_server
checks refusals
checks plan "$CASES/measurements_example.json"

# A patient job and the CLI's `patient` on the same landmarks: the same model.
checks clinic "$CASES/patient_example.json" "$work/patient_job.json"
"$BIN" -q patient "$CASES/patient_example.json" --set geometry.mesh_size=0.012 --tolerance 4 \
  --out "$work/patient_cli" > /dev/null
/usr/bin/python3 - "$work/patient_job.json" "$work/patient_cli/patient_model.json" <<'PY'
import json, sys
app = json.load(open(sys.argv[1]))["summary"]["patient_model"]
cli = json.load(open(sys.argv[2]))
for a, c in zip(app["sides"], cli["sides"], strict=True):
    for k in ("R_m", "H_m", "stiffness_factor"):
        assert abs(a[k] - c[k]) <= 1e-12 * abs(c[k]), (a["side"], k, a[k], c[k])
    assert a["achieved"] == c["achieved"] and a["notch_m"] == c["notch_m"], a["side"]
print("patient job = CLI patient")
PY

# A surgery job and the CLI on the same keys: the same numbers.
overrides='{"geometry.mesh_size": 0.012, "postures.names": ["standing", "supine"]}'
checks surgery "$overrides" "$work/job.json"
: > "$work/empty.toml"
"$BIN" -q surgery "$work/empty.toml" --set geometry.mesh_size=0.012 --set postures.names=standing,supine \
  --out "$work/cli" > /dev/null
/usr/bin/python3 - "$work/job.json" "$work/cli/summary.json" <<'PY'
import json, sys
job = json.load(open(sys.argv[1]))
app, cli = job["summary"], json.load(open(sys.argv[2]))
def same(a, b, what):
    assert abs(a - b) <= 1e-9 * max(1.0, abs(b)), (what, a, b)
for k in ("resected_volume_m3", "resected_volume_mesh_m3", "volume_pre_m3", "volume_remaining_m3"):
    same(app[k], cli[k], k)
for stage in ("preop", "postop"):
    for p, q in zip(app[stage], cli[stage], strict=True):
        for k in ("projection_m", "z_min_m", "z_max_m", "volume_m3", "energy_J"):
            same(p[k], q[k], f"{stage} {p['posture']} {k}")
        for a, b in zip(p["nipple_m"], q["nipple_m"]):
            same(a, b, f"{stage} {p['posture']} nipple")
s = job["record"]["summary"]
same(s["resected_volume_cm3"], 1e6 * cli["resected_volume_m3"], "cm3")
same(s["resected_weight_g"], 970 * 1e3 * cli["resected_volume_m3"], "weight from rho")
same(s["postures"][0]["post"]["nipple_to_base_mm"], 1e3 * cli["postop"][0]["nipple_m"][1], "nipple to base")
# The lower-pole share's surface integral: the volume in front of the chest wall is the body's
# up to the base's spring displacement (a few mm: within 8 %).
for p in s["postures"]:
    for stage in ("pre", "post"):
        v = p[stage]
        assert abs(v["volume_front_cm3"] / v["volume_cm3"] - 1) < 0.08, (p["posture"], stage, v)
        assert 0.2 < v["lower_pole_share"] < 0.8, v
print("ok: the job's numbers equal the CLI's (%.3f cm3 resected, standing nipple to base %.2f mm)"
      % (s["resected_volume_cm3"], s["postures"][0]["post"]["nipple_to_base_mm"]))
PY

# A calibration job and the CLI's `calibrate` on the same data: the same fit.
checks calibrate "$CASES/measurements_example.json" "$work/calibration.json"
"$BIN" -q calibrate "$CASES/measurements_example.json" --set geometry.mesh_size=0.012 --fit mu,c \
  --max-evals 12 --out "$work/cli-calibration" > /dev/null
/usr/bin/python3 - "$work/calibration.json" "$work/cli-calibration/report.json" <<'PY'
import json, sys
app, cli = json.load(open(sys.argv[1]))["report"], json.load(open(sys.argv[2]))
for p, q in zip(app["fit"], cli["fit"], strict=True):
    assert p["name"] == q["name"] and abs(p["fitted"] / q["fitted"] - 1) < 1e-9, (p, q)
assert abs(app["misfit"]["chi2_after"] / cli["misfit"]["chi2_after"] - 1) < 1e-9
print("ok: the calibration job's fit equals the CLI's (%s)" % ", ".join(
    "%s = %.4g" % (p["name"], p["fitted"]) for p in app["fit"]))
PY

# A failing solve and a crashing job process (SIGKILL) end their jobs, not the server.
# The Patient step's files: a recording (calibrate fits its points) and a scan (scan-model ->
# neutral-state -> simulate), each against the CLI on the same file.
uploads() { /usr/bin/python3 "$HERE/upload_checks.py" "$port" "$@"; }
"$BIN" -q record "$CASES/default.toml" --seed 7 --mesh-size 0.012 --points 200 --out "$work/rec.json"
uploads recording "$work/rec.json" "$work/data" "$work/rec_job.json"
"$BIN" -q calibrate "$work/rec.json" --set geometry.mesh_size=0.012 --fit mu --out "$work/cli-rec" > /dev/null
"$BIN" -q synthetic-patient --volume 400 --ptosis 0.3 --lateral 0.1 --asymmetry 0.15 --mesh-size 0.01 \
  --posture standing --out "$work/patient" > /dev/null
uploads scan "$work/patient/scan.stl" "$work/data" "$work/scan_job.json"
"$BIN" -q scan-model "$work/patient/scan.stl" --units mm --posture standing --mesh-size 0.01 --out "$work/cli-scan" > /dev/null
"$BIN" -q neutral-state "$work/cli-scan/case.toml" --posture standing --out "$work/cli-neutral" > /dev/null
"$BIN" -q simulate "$work/cli-neutral/case.reference.toml" --set postures.names=standing,supine,all_fours \
  --out "$work/cli-sim" > /dev/null
/usr/bin/python3 - "$work" <<'PY'
import json, sys
w = sys.argv[1]
load = lambda *p: json.load(open("/".join((w,) + p)))
rec_job, cli = load("rec_job.json"), load("cli-rec", "diagnosis.json")["final"]["parameters"][0]
app = rec_job["summary"]["parameters"][0]
assert abs(app["fitted"] / cli["value"] - 1) < 1e-9 and all(
    abs(a / b - 1) < 1e-9 for a, b in zip(app["interval_95"], cli["interval95"])), (app, cli)
print("ok: the recording's calibration equals the CLI's (mu = %.6g Pa, [%.4g, %.4g])" % (app["fitted"], *app["interval_95"]))
scan_id = load("scan_job.json")["id"]
job = "data/jobs/" + scan_id
for app_file, cli_file, keys in [("model/summary.json", "cli-scan/summary.json", ("scan_points", "tetrahedra", "volume_m3", "fit_rms_m")),
                                 ("neutral/summary.json", "cli-neutral/summary.json", ("converged",))]:
    a, b = load(job, app_file), load(cli_file)
    assert all(a[k] == b[k] for k in keys), (app_file, [(k, a[k], b[k]) for k in keys])
    if "iterations" in a:
        assert a["iterations"] == b["iterations"], "neutral-state iterations differ"
a, b = load(job, "result/summary.json")["postures"], load("cli-sim", "summary.json")["postures"]
assert [p["posture"] for p in a] == [p["posture"] for p in b]
for p, q in zip(a, b):
    for k in ("projection_m", "z_min_m", "volume_m3"):
        assert abs(p[k] - q[k]) <= 1e-9 * max(1, abs(q[k])), (p["posture"], k, p[k], q[k])
print("ok: the scan job's model, neutral state and postures equal scan-model, neutral-state and simulate "
      "on the same file (%d tetrahedra, standing projection %.2f mm)" % (load(job, "model/summary.json")["tetrahedra"],
                                                                       1e3 * a[0]["projection_m"]))
PY

# A breast of the consultation as its scan: the patient job on the upload equals the CLI's
# `patient` on the same file.
uploads consult_scan "$work/patient/scan.stl" "$work/scan_job.json" "$CASES/patient_example.json" "$work/consult_scan.json"
/usr/bin/python3 - "$CASES/patient_example.json" "$work/patient/scan.stl" "$work/consult_patient.json" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
doc["left"] = {"scan": {"file": sys.argv[2], "units": "mm"}, "sn_n": doc["left"]["sn_n"],
               "nipple_midline": doc["left"]["nipple_midline"]}
json.dump(doc, open(sys.argv[3], "w"))
PY
"$BIN" -q patient "$work/consult_patient.json" --set geometry.mesh_size=0.012 --tolerance 4 --out "$work/cli-consult" > /dev/null
/usr/bin/python3 - "$work/consult_scan.json" "$work/cli-consult/patient_model.json" <<'PY'
import json, sys
app = json.load(open(sys.argv[1]))["summary"]["patient_model"]["sides"][0]
cli = json.load(open(sys.argv[2]))["sides"][0]
assert app["side"] == cli["side"] == "left" and "scan" in app
for k in ("n_imf_mm", "base_width_mm", "sn_n_mm"):
    assert abs(app["achieved"][k] - cli["achieved"][k]) < 1e-9, (k, app["achieved"][k], cli["achieved"][k])
for k in ("mean", "p95", "max"):
    assert abs(app["scan"]["model_to_scan_mm"][k] - cli["scan"]["model_to_scan_mm"][k]) < 1e-9, k
print("ok: the consultation's scanned breast equals the CLI's `patient` on the same scan (model %.1f mm from it)"
      % app["scan"]["model_to_scan_mm"]["mean"])
PY

# Surgery on the scanned breast: the app's job on the scan job's neutral case equals the CLI's
# `breastsim surgery` on that case file with the same plan.
uploads scan_surgery "$work/scan_job.json" "$work/scan_surgery.json"
scan_id=$(/usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["id"])' "$work/scan_job.json")
"$BIN" -q surgery "$work/data/jobs/$scan_id/neutral/case.reference.toml" --set incision.a_deg=35 \
  --set postures.names=standing --out "$work/cli-scan-surgery" > /dev/null
/usr/bin/python3 - "$work/scan_surgery.json" "$work/cli-scan-surgery/summary.json" <<'PY'
import json, sys
job = json.load(open(sys.argv[1]))
app, cli = job["summary"], json.load(open(sys.argv[2]))
def same(a, b, what):
    assert abs(a - b) <= 1e-9 * max(1.0, abs(b)), (what, a, b)
assert app["model"] == cli["model"] == "full breast"
for k in ("resected_volume_m3", "resected_volume_mesh_m3", "volume_pre_m3", "volume_remaining_m3"):
    same(app[k], cli[k], k)
for k in ("max_gap_keel_m", "max_gap_chest_m"):
    same(app["suture"][k], cli["suture"][k], k)
for stage in ("preop", "postop"):
    for p, q in zip(app[stage], cli[stage], strict=True):
        for a, b in zip(p["nipple_m"], q["nipple_m"], strict=True):
            same(a, b, f"{stage} {p['posture']} nipple")
s = job["record"]["summary"]
same(s["resected_volume_cm3"], 1e6 * cli["resected_volume_m3"], "cm3")
same(s["max_gap_keel_mm"], 1e3 * cli["suture"]["max_gap_keel_m"], "keel gap")
same(s["max_gap_chest_mm"], 1e3 * cli["suture"]["max_gap_chest_m"], "chest gap")
same(s["postures"][0]["post"]["nipple_to_base_mm"], 1e3 * cli["postop"][0]["nipple_m"][1], "new nipple to base")
print("ok: the scanned breast's surgery equals the CLI's on the scan's neutral case (%.3f cm3 resected, "
      "new nipple y, z = %.2f, %.2f mm)" % (s["resected_volume_cm3"], *[1e3 * v for v in cli["postop"][0]["nipple_m"][1:]]))
PY

checks failures | tee "$work/failures.txt"
victim=$(tail -1 "$work/failures.txt")
job_pid=$(pgrep -f -- "--run-job $work/data/jobs/$victim" | head -1)
[ -n "$job_pid" ] && kill -KILL "$job_pid"
checks crashed "$victim" "$work/data/jobs/$victim"

# Cancel: nothing of the cancelled jobs is left but their records.
checks cancel | tee "$work/cancel.txt"
ids=$(tail -1 "$work/cancel.txt")
for id in $(echo "$ids" | tr -d '[]",'); do
  left=$(ls -A "$work/data/jobs/$id" | grep -v -E '^(job.json|request.json|log.txt|output.txt)$' || true)
  [ -z "$left" ] || { echo "cancelled job $id left: $left"; exit 1; }
done
echo "ok: cancelled jobs left no result and no staging folder"

# Restart (with two workers): the finished job is found again; two jobs run at once.
stop_server
start_server --workers 2
checks persisted "$work/job.json"
checks parallel
# Only what the server wrote is in the data folder.
extra=$(find "$work/data" -mindepth 1 -maxdepth 1 ! -name jobs ! -name uploads ! -name .breastsim-app)
[ -z "$(ls -A "$work/data/uploads")" ] || { echo "files left in --data/uploads"; exit 1; }
[ -z "$extra" ] || { echo "unexpected in --data: $extra"; exit 1; }
stop_server
echo "server.sh: all checks passed"
