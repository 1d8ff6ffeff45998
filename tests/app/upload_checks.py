# SPDX-License-Identifier: LGPL-3.0-or-later
"""Checks of the Patient step's files and of the structured progress (tests/app/server.sh).

Usage: upload_checks.py PORT PHASE [ARGS...]
  recording REC_JSON DATA OUT the recording check and its refusals; a calibration job fitting
                              its points (fit mu); the job's summary to OUT
  scan SCAN_STL DATA OUT      refused uploads (unit, format, fields, traversal, truncated and
                              foreign files, content types, sizes: nothing stored, no job); a
                              scan job: the stored bytes, its progress channel, the scanned
                              breast in three postures, unmirrored; its summary to OUT
  scan_surgery SCAN_JOB OUT   refused scanned-breast surgeries (an unknown or non-scan job, a cap
                              key, an incision the scanned skin cannot hold: the library's message);
                              a surgery on the scan job's neutral case (standing), its progress
                              channel as surgery()'s; the record and summary.json to OUT
surgery_progress() is called by server_checks.py on the surgery job it runs.
"""
import json
import os
import socket
import sys

from api_client import Api


def check(cond, what):
    if not cond:
        raise AssertionError(what)
    print("ok:", what)


def channel(api, job_id):
    s, _, data = api.raw("GET", f"/api/jobs/{job_id}/files/progress.jsonl")
    assert s == 200, (s, data[:200])
    return [json.loads(line) for line in data.decode().splitlines()]


def surgery_progress(api, job_id, seen, postures):
    """The surgery's stages as the library reports them, and the record's bar from them."""
    by_stage = surgery_channel(api, job_id, postures)
    running = [(p, st) for p, st in seen if st != "starting"]
    check(running and all(st in by_stage and abs(p - min(by_stage[st], 0.99)) < 1e-12 for p, st in running) and
          all(a[0] <= b[0] for a, b in zip(running, running[1:])),
          f"the record's progress while it ran is the channel's last entry ({len(running)} polls, "
          f"{len(set(running))} distinct stages seen, non-decreasing)")


def surgery_channel(api, job_id, postures):
    """The surgery's stages in its progress channel as surgery() reports them: {stage: fraction}."""
    n = len(postures)
    stages = (["meshing"] + [f"pre-operative posture {p} ({k + 1} of {n})" for k, p in enumerate(postures)] +
              ["sutures"] + [f"post-operative posture {p} ({k + 1} of {n})" for k, p in enumerate(postures)] +
              ["finished"])  # the app's jobs make no pictures (output.pictures = none)
    entries = channel(api, job_id)
    total = 2 * n + 2
    check([e["stage"] for e in entries] == stages and [e["n"] for e in entries] == list(range(1, len(stages) + 1)) and
          all(abs(e["fraction"] - k / total) < 1e-12 for k, e in enumerate(entries[:-1])) and entries[-1]["fraction"] == 1,
          f"the surgery's progress channel: {len(entries)} stages in order at k / {total} "
          f"({', '.join(e['stage'] for e in entries)})")
    return {e["stage"]: e["fraction"] for e in entries}


def recording(api, rec_file, data, out):
    rec = json.load(open(rec_file))
    s, r = api.json("POST", "/api/recording/check", rec)
    check(s == 200 and r["ok"] and r["points"] == sum(len(p["points"]) for p in rec["postures"]) and
          [p["name"] for p in r["postures"]] == [p["name"] for p in rec["postures"]],
          f"a recording is checked ({r.get('points')} points in {[p['name'] for p in r['postures']]})")
    mm = json.loads(json.dumps(rec))
    mm["postures"][0]["points"][0] = [1e3 * x for x in mm["postures"][0]["points"][0]]
    s, r = api.json("POST", "/api/recording/check", mm)
    check(s == 200 and not r["ok"] and "key 'postures[0].points[0][0]'" in r["error"],
          f"a point in millimetres is refused with the library's message ({r['error'][:90]} ...)")
    big = json.loads(json.dumps(rec))
    big["postures"][0]["points"] = [[0.01, 0.02, 0.03]] * 20001  # short numbers: under the body size limit
    s, r = api.json("POST", "/api/recording/check", big)
    check(s == 200 and not r["ok"] and "is out of range: allowed [10, 20000]" in r["error"],
          f"more than 20000 points are refused ({r['error'][:70]} ...)")
    for what, body in [("both data fields", {"recording": rec, "measurements": {"units": "SI"}}),
                       ("a bad recording", {"recording": mm}),
                       ("a recording that is not one", {"recording": {"format": "breastsim-recording/9"}})]:
        s, r = api.json("POST", "/api/jobs", {"kind": "calibrate", "fit": "mu", **body})
        check(s == 400, f"a calibration with {what} is refused before any job: {r['error'][:80]}")
    s, r = api.json("POST", "/api/jobs", {"kind": "calibrate", "overrides": {"geometry.mesh_size": 0.012},
                                          "recording": rec, "fit": "mu"})
    check(s == 202, f"a calibration from the recording is queued ({s} {r})")
    job = api.wait(r["id"], ("done", "failed", "cancelled"), 600)
    mu = job["summary"]["parameters"][0] if job["state"] == "done" else {}
    check(job["state"] == "done" and job["options"]["data"] == "recording" and mu.get("name") == "mu" and
          mu["interval_95"][0] < mu["fitted"] < mu["interval_95"][1] and "recording.json" in os.listdir(
              os.path.join(data, "jobs", r["id"])),
          f"the recording's fit: mu = {mu.get('fitted', 0):.4g} Pa {mu.get('interval_95')} "
          f"({job['summary'].get('stop_reason', job['error'])[:60]} ...)")
    json.dump(job, open(out, "w"))


def post_scan(api, query, body, ctype="application/octet-stream"):
    s, _, data = api.raw("POST", "/api/scans" + query, body, {"Content-Type": ctype})
    return s, json.loads(data)


def declared_length(port, path, length, ctype):
    """A POST that announces `length` bytes and sends none: answered before the body is read."""
    with socket.create_connection(("127.0.0.1", port), timeout=10) as c:
        c.sendall(f"POST {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: {ctype}\r\n"
                  f"Content-Length: {length}\r\n\r\n".encode())
        return int(c.recv(4096).split(b" ", 2)[1])


def scan_refusals(api, stl, data):
    jobs_before = len(api.json("GET", "/api/jobs")[1]["jobs"])
    q = "?format=stl&units=mm&posture=standing"
    for query, body, ctype, status, text in [
        ("?format=stl&units=cm", stl, None, 400, "units = 'cm': the unit of the scan's coordinates must be stated"),
        ("?format=stl", stl, None, 400, "the unit of the scan's coordinates must be stated: mm or m"),
        ("?format=stl&units=m", stl, None, 400, "wrong units? the scan spans"),
        ("?format=xyz&units=mm", stl, None, 400, "format = 'xyz': allowed obj, ply, stl"),
        ("?format=ply&units=mm", stl, None, 400, "not a PLY file"),
        ("?format=stl&units=mm&posture=prone", stl, None, 400, "posture = 'prone': allowed"),
        ("?format=stl&units=mm&mesh_size=0.5", stl, None, 400, "mesh_size = 0.5 is out of range"),
        ("?format=stl&units=mm&mesh_size=1e-9", stl, None, 400, "mesh_size = 1e-9 is out of range"),
        ("?format=stl&units=mm&format=ply", stl, None, 400, "field 'format' is given 2 times"),
        (q + "&file=../../etc/passwd", stl, None, 400, "field 'file' is not allowed in a scan upload"),
        ("?format=../../etc/passwd&units=mm", stl, None, 400, "format = '../../etc/passwd': allowed"),
        ("?format=stl%2f..%2f..%2fx&units=mm", stl, None, 400, "format = 'stl/../../x': allowed"),
        (q, stl[:5000], None, 400, "truncated binary STL"),
        (q, b"", None, 400, "the uploaded scan"),
        (q, b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n", None, 400, "the uploaded scan"),
        (q, stl, "text/plain", 415, "application/octet-stream"),
        (q, stl, "application/json", 415, "application/octet-stream"),
    ]:
        s, r = post_scan(api, query, body, ctype or "application/octet-stream")
        check(s == status and text in r["error"] and data not in r["error"],
              f"scan upload {query[:40]} ({len(body)} bytes, {ctype or 'octet-stream'}) refused {s}: {r['error'][:90]}")
    for path in ["/api/scans/../jobs", "/api/scans/..%2f..%2fetc%2fpasswd", "/api/%2e%2e/scans"]:
        s, _, _ = api.raw("POST", path + q, stl, {"Content-Type": "application/octet-stream"})
        check(s in (404, 415), f"POST {path} with a scan's bytes is refused ({s}: not a route, or not JSON)")
    for path in ("/etc/passwd", os.path.join(data, "jobs")):
        s, r = api.json("POST", "/api/validate", {"geometry.mesh_file": path})
        check(s == 400 and "no file path from a request" in r["error"],
              f"a mesh file named by a request is refused before any file is looked at: {r['error'][:80]}")
    s = declared_length(api.port, "/api/scans" + q, 1 << 30, "application/octet-stream")
    s2 = declared_length(api.port, "/api/jobs", 2 << 20, "application/json")
    check(s == 413 and s2 == 413, "a scan above --max-upload and a JSON body above --max-body are refused "
                                  f"before they are read ({s}, {s2})")
    left = os.listdir(os.path.join(data, "uploads"))
    check(left == [] and len(api.json("GET", "/api/jobs")[1]["jobs"]) == jobs_before,
          "no refused upload is kept and none made a job")


def scan(api, stl_file, data, out):
    stl = open(stl_file, "rb").read()
    scan_refusals(api, stl, data)
    s, r = post_scan(api, "?format=stl&units=mm&posture=standing&mesh_size=0.01", stl)
    check(s == 202, f"a synthetic patient's scan is accepted ({s} {r})")
    stored = os.path.join(data, "jobs", r["id"], "scan.stl")
    check(open(stored, "rb").read() == stl, f"the upload is stored in its job's folder as scan.stl ({len(stl)} bytes)")
    job = api.wait(r["id"], ("done", "failed", "cancelled"), 600)
    check(job["state"] == "done", f"the scan job is done ({job['state']}: {job['error']})")
    stages = [e["stage"] for e in channel(api, r["id"])]
    check(stages[:3] == ["scan model: fit and mesh of the skin", "neutral state: the stress-free breast of the scan",
                         "simulate: meshing"] and stages[-1] == "simulate: finished" and len(stages) == 7,
          f"its progress channel: {', '.join(stages)}")
    sm = job["summary"]
    postures = [p["posture"] for p in sm["postures"]]
    docs = [api.json("GET", f"/api/jobs/{r['id']}/files/surface_{p}.json")[1] for p in postures]
    check(postures == ["standing", "supine", "all_fours"] and all(d["mirror_x"] is False for d in docs) and
          sm["neutral"]["converged"] and sm["scan"]["points"] > 300,
          f"the scanned breast in three postures, full (unmirrored): {sm['scan']['points']} points, "
          f"{sm['scan']['volume_cm3']:.1f} cm3, standing nipple to base {sm['postures'][0]['pre']['nipple_to_base_mm']:.1f} mm")
    for name in ("scan_model_summary.json", "neutral_summary.json", "progress.jsonl"):
        check(api.raw("GET", f"/api/jobs/{r['id']}/files/{name}")[0] == 200, f"{name} is served")
    s, r2 = api.json("POST", "/api/jobs", {"kind": "scan", "scan": {"file": "../../etc/passwd"}})
    check(s == 400, "a scan job cannot be posted as a job request (only by an upload)")
    json.dump(job, open(out, "w"))


def scan_surgery(api, scan_job_file, out):
    scan_id = json.load(open(scan_job_file))["id"]
    plan = {"incision.a_deg": 35, "postures.names": ["standing"]}
    for body, what in [({"scan": "0123456789abcdef"}, "not a finished scan job"),
                       ({"scan": "../../etc"}, "expected the id of a finished scan job"),
                       ({"scan": scan_id, "overrides": {"geometry.R": 0.07}},
                        "key 'geometry.R' is not applied to the surgery of a scanned breast")]:
        s, r = api.json("POST", "/api/jobs", {"kind": "surgery", "overrides": plan, **body})
        check(s == 400 and what in r["error"], f"a scanned breast's surgery refused: {r.get('error')}")
    s, r = api.json("POST", "/api/jobs", {"kind": "surgery", "scan": scan_id,
                                          "overrides": {**plan, "incision.h": 0.3}})
    check(s == 202, f"an incision is checked on the scanned skin by the job ({s} {r})")
    job = api.wait(r["id"], ("done", "failed", "cancelled"), 600)
    check(job["state"] == "failed" and job["error_kind"] == "input" and "incision.h" in job["error"],
          f"an impossible plan on the scanned breast fails with the library's message ({job['error']})")
    s, r = api.json("POST", "/api/jobs", {"kind": "surgery", "scan": scan_id, "overrides": plan})
    check(s == 202, f"a surgery on the scanned breast is accepted ({s} {r})")
    job = api.wait(r["id"], ("done", "failed", "cancelled"), 600)
    check(job["state"] == "done", f"the scanned breast's surgery is done ({job['state']}: {job['error']})")
    surgery_channel(api, r["id"], ["standing"])
    sm = job["summary"]
    check(sm["model"] == "full breast" and sm["resected_volume_cm3"] > 0 and len(sm["postures"]) == 1,
          f"full-breast surgery: {sm['resected_volume_cm3']:.1f} cm3 resected, gaps keel "
          f"{sm['max_gap_keel_mm']:.4f} mm, chest {sm['max_gap_chest_mm']:.4f} mm")
    s, _, data = api.raw("GET", f"/api/jobs/{r['id']}/files/summary.json")
    check(s == 200, "its summary.json is served")
    json.dump({"record": job, "summary": json.loads(data)}, open(out, "w"))


def consult_scan(api, stl_file, scan_job_file, patient_file, out):
    """A breast of the consultation as its standing scan: uploaded for the
    consultation (kept, not modelled), named by its id in a patient job;
    the refused uploads and patient requests name the field."""
    stl = open(stl_file, "rb").read()
    q = "?format=stl&units=mm"
    for query, text in [(q + "&use=print", "use = 'print': allowed consultation, model"),
                        (q + "&use=consultation&posture=supine", "a consultation's scan is taken standing")]:
        s, r = post_scan(api, query, stl)
        check(s == 400 and text in r["error"], f"consultation upload {query} refused: {r['error'][:80]}")
    s, r = post_scan(api, q + "&use=consultation", stl)
    check(s == 202, f"a scan for the consultation is accepted ({s} {r})")
    upload = r["id"]
    job = api.wait(upload, ("done", "failed", "cancelled"), 60)
    stages = [e["stage"] for e in channel(api, upload)]
    check(job["state"] == "done" and stages == ["scan kept for the consultation"],
          f"it is kept, not modelled ({job['state']}: {stages})")
    doc = json.load(open(patient_file))
    tape = {"sn_n": doc["left"]["sn_n"], "nipple_midline": doc["left"]["nipple_midline"]}
    base = {"kind": "patient", "overrides": {"geometry.mesh_size": 0.012}, "tolerance_mm": 4}
    for scan, what in [({"upload": upload, "file": "/etc/passwd"}, "left.scan.file: not allowed in the app"),
                       ({"upload": upload, "units": "m"}, "left.scan.units: not allowed in the app"),
                       ({"upload": "../../etc"}, "left.scan.upload = \"../../etc\": expected the id of the uploaded scan"),
                       ({}, "left.scan.upload = null: expected the id")]:
        s, r = api.json("POST", "/api/jobs", {**base, "patient": {**doc, "left": {"scan": scan, **tape}}})
        check(s == 400 and what in r["error"], f"a scanned side refused: {r.get('error', '')[:90]}")
    model_scan = json.load(open(scan_job_file))["id"]
    for other, what in [("0123456789abcdef", "no such upload"), (model_scan, "not a scan uploaded for the consultation")]:
        s, r = api.json("POST", "/api/jobs", {**base, "patient": {**doc, "left": {"scan": {"upload": other}, **tape}}})
        rec = api.wait(r["id"], ("done", "failed", "cancelled"), 120)
        check(rec["state"] == "failed" and what in rec["error"], f"a patient job on another upload fails: {rec['error'][:90]}")
    s, r = api.json("POST", "/api/jobs", {**base, "patient": {**doc, "left": {"scan": {"upload": upload}, **tape}}})
    rec = api.wait(r["id"], ("done", "failed", "cancelled"), 600)
    check(rec["state"] == "done", f"the patient job on the uploaded scan is done ({rec['state']}: {rec['error']})")
    json.dump(rec, open(out, "w"))


if __name__ == "__main__":
    api = Api(int(sys.argv[1]))
    phase = sys.argv[2]
    if phase == "recording":
        recording(api, sys.argv[3], sys.argv[4], sys.argv[5])
    elif phase == "scan":
        scan(api, sys.argv[3], sys.argv[4], sys.argv[5])
    elif phase == "consult_scan":
        consult_scan(api, sys.argv[3], sys.argv[4], sys.argv[5], sys.argv[6])
    elif phase == "scan_surgery":
        scan_surgery(api, sys.argv[3], sys.argv[4])
    else:
        sys.exit(f"unknown phase {phase}")
