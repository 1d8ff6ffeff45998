# SPDX-License-Identifier: LGPL-3.0-or-later
"""Checks of `breastsim serve` over HTTP, one phase per call (tests/app/server.sh).

Usage: server_checks.py PORT PHASE [ARGS...]
  refusals                    malformed, unknown, out-of-range, oversized, traversal, CORS, Host, sweeps
  plan                        keys, validate, incision check, measurements check
  surgery OVERRIDES_JSON OUT  run a surgery job (its progress channel) and its report; write its record and summary.json to OUT
  calibrate MEASUREMENTS OUT  refused fit names; a small calibration; its record and report to OUT
  failures                    a failing solve; starts a job and prints its id (to be killed)
  crashed ID FOLDER           the killed job is failed, its staging folder gone, the server up
  cancel                      cancel a queued and a running job; nothing of them is left
  parallel                    (--workers 2) two jobs run at once; a running job's log is served
  persisted RECORD_JSON       the job of RECORD_JSON is still there with the same summary
"""
import io
import json
import os
import socket
import tarfile
import sys
import time

from api_client import Api
from upload_checks import surgery_progress


def check(cond, what):
    if not cond:
        raise AssertionError(what)
    print("ok:", what)


def refusals(api):
    s, r = api.json("POST", "/api/validate", {"incision.a_deg": 95})
    check(s == 400 and r["error"] == "key 'incision.a_deg' = 95 is out of range: allowed (0, 90) deg",
          f"out-of-range value -> 400 with the CLI's message ({r})")
    s, r = api.json("POST", "/api/validate", {"no.such_key": 1})
    check(s == 400 and "unknown key 'no.such_key'" in r["error"], f"unknown key -> 400 ({r})")
    s, r = api.json("POST", "/api/validate", {"geometry.order": "two"})
    check(s == 400 and "geometry.order" in r["error"], f"wrong type -> 400 naming the key ({r})")
    s, r = api.json("POST", "/api/validate", {"solver.petsc_options": "-log_view :/tmp/x"})
    check(s == 400 and "solver.petsc_options" in r["error"], "PETSc options (they can name files) refused")
    s, r = api.json("POST", "/api/jobs", {"kind": "rm -rf", "overrides": {}})
    check(s == 400 and "kind" in r["error"], f"unknown job kind -> 400 ({r})")
    s, r = api.json("POST", "/api/jobs", {"kind": "surgery", "overrides": {"incision.s": 0.5}})
    check(s == 400 and "incision.s" in r["error"], f"impossible incision refused before any job ({r})")
    for body in ['{"a": ', "[1, 2", "\x00\x01", "{" * 5000 + "}" * 5000, '"just text"', "null"]:
        s, _, data = api.raw("POST", "/api/validate", body, {"Content-Type": "application/json"})
        check(s == 400 and b'"error"' in data, f"malformed body {body[:12]!r}... -> 400 ({s})")
    s, _, _ = api.raw("POST", "/api/validate", "{}", {"Content-Type": "text/plain"})
    check(s == 415, f"a body that is not application/json -> 415 (cross-site forms) ({s})")
    big = '{"case.name": "' + "x" * (2 << 20) + '"}'
    s, _, _ = api.raw("POST", "/api/validate", big, {"Content-Type": "application/json"})
    check(s == 413, f"oversized body -> 413 ({s})")
    for path in ["/api/jobs/../../etc/passwd", "/api/jobs/%2e%2e/%2e%2e/etc/passwd",
                 "/api/jobs/%2e%2e%2f%2e%2e%2fetc%2fpasswd", "/../../../../etc/passwd",
                 "/three/../../../../../etc/passwd", "/three/%2e%2e/%2e%2e/package.json",
                 "/api/jobs/0123456789abcdef/files/..%2f..%2f..%2fetc%2fpasswd",
                 "/api/jobs/0123456789abcdef/files/%2e%2e", "/api/jobs/0123456789ABCDEF",
                 "/api/jobs/0123456789abcdef0/files/job.json", "//etc/passwd", "/app.js/../../.."]:
        s, _, data = api.raw("GET", path)
        check(s in (400, 404) and b"root:" not in data, f"traversal {path} -> {s}")
    s, h, _ = api.raw("GET", "/api/keys", headers={"Origin": "http://evil.example"})
    check(s == 200 and not any(k.lower().startswith("access-control") for k in h),
          "no Access-Control-* header (CORS closed)")
    s, h, _ = api.raw("OPTIONS", "/api/jobs", headers={"Origin": "http://evil.example",
                                                       "Access-Control-Request-Method": "POST"})
    check(not any(k.lower().startswith("access-control") for k in h), f"preflight not granted ({s})")
    s, _, _ = api.raw("GET", "/api/keys", headers={"Host": "evil.example:80"})
    check(s == 403, f"a Host header of another machine (DNS rebinding) -> 403 ({s})")
    header_refusals(api.port)
    slow_clients(api.port)


def raw_status(port, request, timeout=10):
    """Send the bytes `request` on a new connection; the reply's status code (0: none)."""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as c:
        c.sendall(request)
        reply = b""
        try:
            while b"\r\n" not in reply:
                chunk = c.recv(4096)
                if not chunk:
                    break
                reply += chunk
        except (ConnectionResetError, socket.timeout):
            pass
    parts = reply.split(b" ", 2)
    return int(parts[1]) if len(parts) > 1 and parts[1].isdigit() else 0


def header_refusals(port):
    host = f"127.0.0.1:{port}".encode()
    ok = b"GET /api/keys HTTP/1.1\r\nHost: " + host + b"\r\nConnection: close\r\n\r\n"
    check(raw_status(port, ok) == 200, "a well-formed raw request -> 200")
    cases = {
        "two Host headers, the second foreign":
            b"GET /api/keys HTTP/1.1\r\nHost: " + host + b"\r\nHost: evil.example\r\nConnection: close\r\n\r\n",
        "an empty Host": b"GET /api/keys HTTP/1.1\r\nHost: \r\nConnection: close\r\n\r\n",
        "no Host on HTTP/1.1": b"GET /api/keys HTTP/1.1\r\nConnection: close\r\n\r\n",
        "two different Content-Length values":
            b"POST /api/validate HTTP/1.1\r\nHost: " + host + b"\r\nContent-Type: application/json\r\n"
            b"Content-Length: 2\r\nContent-Length: 40\r\nConnection: close\r\n\r\n{}",
        "Content-Length with Transfer-Encoding":
            b"POST /api/validate HTTP/1.1\r\nHost: " + host + b"\r\nContent-Type: application/json\r\n"
            b"Content-Length: 2\r\nTransfer-Encoding: chunked\r\nConnection: close\r\n\r\n{}",
        "10,000 header lines":
            b"GET /api/keys HTTP/1.1\r\nHost: " + host + b"\r\n"
            + b"".join(b"X-H%d: v\r\n" % i for i in range(10000)) + b"Connection: close\r\n\r\n",
    }
    for what, request in cases.items():
        s = raw_status(port, request)
        check(s == 400, f"{what} -> 400 ({s})")


def slow_clients(port, n=30):
    """n connections that trickle their headers do not hold up a normal request."""
    slow = []
    for _ in range(n):
        c = socket.create_connection(("127.0.0.1", port), timeout=10)
        c.sendall(b"GET /api/keys HTTP/1.1\r\nHo")
        slow.append(c)
    try:
        time.sleep(0.5)
        for c in slow:  # one more byte each: still sending, never finishing
            c.sendall(b"s")
        t0 = time.monotonic()
        s, _, _ = Api(port, timeout=10).raw("GET", "/api/keys")
        took = time.monotonic() - t0
        check(s == 200 and took < 2.0, f"a normal request beside {n} slow clients -> {s} in {took:.2f} s")
    finally:
        for c in slow:
            c.close()


def sweep_refusals(api):
    base = {"kind": "sweep", "overrides": {"geometry.mesh_size": 0.012}}
    for vary, what in [(None, "vary: an object"), ({"a": [25], "h": [0.02], "d": [0.04]}, "vary: an object"),
                       ({"tissue.mu": [300, 400]}, "not one of the incision's"), ({"a": [25, 30, 35, 40]}, "1 to 3 numbers"),
                       ({"a": ["25"]}, "is not a number"), ({"a": [95]}, "incision.a_deg"),
                       ({"no_such": [1]}, "no_such")]:
        body = dict(base) if vary is None else {**base, "vary": vary}
        s, r = api.json("POST", "/api/jobs", body)
        check(s == 400 and what in r["error"], f"sweep refused: {vary} ({r['error'][:70]})")


def plan(api):
    s, r = api.json("GET", "/api/keys")
    keys = {k["key"]: k for k in r["keys"]}
    check(s == 200 and keys["incision.a_deg"]["allowed"] == "(0, 90)", "keys: schema with the ranges")
    s, r = api.json("POST", "/api/validate", {"incision.a_deg": 35, "geometry.mesh_size": 0.01})
    check(s == 200 and r["ok"] and "a_deg = 35" in r["case_toml"], "validate: resolved case TOML")
    s, r = api.json("POST", "/api/incision/check", {"incision.a_deg": 30, "incision.s": 0.02})
    check(s == 200 and r["C"] == [0.0, 0.0, -0.045] and abs(r["A"][2] - 0.02) < 1e-12,
          f"incision points A..D and planes ({r['A']}, {r['C']})")
    s, r = api.json("POST", "/api/incision/check", {"incision.h": 0.3})
    check(s == 200 and not r["ok"] and "incision.h" in r["error"], f"impossible incision: the reason names h ({r})")
    s, r = api.json("POST", "/api/incision/check", {"incision.a_deg": 90})
    check(s == 400 and "incision.a_deg" in r["error"], f"a value outside the key's range: 400 ({r})")
    doc = json.load(open(sys.argv[3])) if len(sys.argv) > 3 else None
    if doc:
        s, r = api.json("POST", "/api/measurements/check", doc)
        check(s == 200 and "standing" in r["postures"], "measurements: the example is accepted")
        doc["postures"][0]["z_min"] = -78.0
        s, r = api.json("POST", "/api/measurements/check", doc)
        check(s == 400 and "z_min" in r["error"] and "mm" in r["error"], f"measurements in mm refused ({r})")


def clinic(api, patient_file, out):
    """Patient and plan jobs: refused requests name the field; a patient job's model is the CLI's."""
    doc = json.load(open(patient_file))
    base = {"kind": "patient", "overrides": {"geometry.mesh_size": 0.012}}
    bad_sn = json.loads(json.dumps(doc))
    bad_sn["left"]["sn_n"] = 240
    for body, what in [(base, "field 'patient' is missing"),
                       ({**base, "patient": bad_sn}, "'left.sn_n' = 240 cm is out of range: [15, 45] cm"),
                       ({**base, "patient": doc, "tolerance_mm": 0}, "tolerance_mm = 0 is out of range"),
                       ({**base, "patient": {**doc, "body": {"height": 300}}},
                        "key 'body.height' = 300 cm is out of range: [120, 220] cm"),
                       ({**base, "patient": {**doc, "body": {"weight": 70}}},
                        "key 'body.weight' is not allowed (did you mean 'weight_kg'?)"),
                       ({**base, "patient": doc, "targets": {}}, "field 'targets' is not allowed in a patient"),
                       ({**base, "kind": "plan", "patient": doc}, "targets: an object"),
                       ({**base, "kind": "plan", "patient": doc, "targets": {"middle": {"grams": 100}}},
                        "targets.middle: the side must be left or right"),
                       ({**base, "kind": "plan", "patient": doc, "targets": {"left": {"grams": 9000}}},
                        "targets.left.grams = 9000 g is out of range: [10, 3000] g"),
                       ({**base, "kind": "plan", "patient": doc, "targets": {"left": {"sn_n": 21}}},
                        "targets.left.sn_n: unknown target"),
                       ({**base, "kind": "plan", "patient": doc, "targets": {"left": {"grams": 100}},
                         "symmetric": "yes"}, "symmetric = \"yes\": expected true or false"),
                       ({**base, "kind": "plan", "patient": {**doc, "right": None}, "targets": {"left": {"grams": 100}}},
                        "key 'right' must be an object")]:
        s, r = api.json("POST", "/api/jobs", body)
        check(s == 400 and what in r["error"], f"{body['kind']} refused: {what} ({r['error'][:80]})")
    # The soft, ptotic left breast's landmarks differ by up to 3 mm between two 12 mm meshes.
    s, r = api.json("POST", "/api/jobs", {**base, "patient": doc, "tolerance_mm": 4})
    check(s == 202, f"patient job accepted ({s} {r})")
    rec = api.wait(r["id"], ("done", "failed", "cancelled"), 600)
    check(rec["state"] == "done", f"patient job done ({rec['state']}: {rec['error']})")
    m = rec["summary"]["patient_model"]
    check([x["side"] for x in m["sides"]] == ["left", "right"] and all(x["largest_error_mm"] <= 4 for x in m["sides"]),
          "patient job: both breasts within the accepted 4 mm of their landmarks")
    s, r = api.json("POST", f"/api/jobs/{rec['id']}/report", {"pictures": []})
    check(s == 404 and "surgery or plan" in r["error"], f"a patient job has no report: 404 ({r})")
    json.dump(rec, open(out, "w"))


def surgery(api, overrides, out):
    s, r = api.json("POST", "/api/jobs", {"kind": "surgery", "overrides": json.loads(overrides)})
    check(s == 202, f"job accepted ({s} {r})")
    seen = []  # (progress, stage) of the record while the job runs
    while True:
        rec = api.wait(r["id"], ("running", "done", "failed", "cancelled"), 600)
        if rec["state"] != "running":
            break
        seen.append((rec["progress"], rec["stage"]))
        time.sleep(0.1)
    check(rec["state"] == "done", f"surgery job done ({rec['state']}: {rec['error']})")
    surgery_progress(api, r["id"], seen, json.loads(overrides)["postures.names"])
    s, _, data = api.raw("GET", f"/api/jobs/{r['id']}/files/summary.json")
    check(s == 200, "summary.json served from the job's whitelist")
    s, h, tar = api.raw("GET", f"/api/jobs/{r['id']}/result.tar")
    names = tarfile.open(fileobj=io.BytesIO(tar)).getnames()
    check(s == 200 and f"breastsim-{r['id']}/summary.json" in names and
          all(n.startswith(f"breastsim-{r['id']}/") and ".." not in n for n in names),
          f"the result folder as one archive ({len(names)} files, {len(tar) >> 10} KiB)")
    report(api, r["id"], rec)
    json.dump({"record": rec, "summary": json.loads(data)}, open(out, "w"))


PNG_1X1 = "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNkYPhfDwAChwGA60e6kgAAAABJRU5ErkJggg=="


def report(api, job_id, rec):
    """The printable report of the finished surgery: refused pictures and ids, then one written."""
    url = f"/api/jobs/{job_id}/report"
    pic = {"caption": "standing", "png": PNG_1X1}
    for body, what in [({"pictures": [{"caption": "x", "png": "not base64!"}]}, "pictures[0].png: not base64"),
                       ({"pictures": [{"caption": "x", "png": "aGVsbG8gd29ybGQ="}]}, "not a PNG file"),
                       ({"pictures": [pic] * 9}, "at most 8 pictures"),
                       ({"pictures": [{"caption": "x" * 201, "png": PNG_1X1}]}, "allowed at most 200"),
                       ({"pictures": [], "calibration": "0123456789abcdef"}, "no finished calibration"),
                       ({"pictures": [], "calibration": "../../etc"}, "16 hex digits"),
                       ({"pictures": [], "script": 1}, "unknown field 'script'")]:
        s, r = api.json("POST", url, body)
        check(s == 400 and what in r["error"], f"report refused: {what} ({r['error'][:60]})")
    s, r = api.json("POST", "/api/jobs/0123456789abcdef/report", {"pictures": []})
    check(s == 404, "a report of a job that does not exist -> 404")
    s, r = api.json("POST", url, {"pictures": [{"caption": "<script>alert(1)</script> & co", "png": PNG_1X1}],
                                  "calibration": None})
    check(s == 200 and r["url"] == f"/api/jobs/{job_id}/files/report.html", f"report written ({r})")
    s, h, html = api.raw("GET", r["url"])
    html = html.decode()
    v = rec["summary"]["resected_volume_cm3"]
    check(s == 200 and h["Content-Type"].startswith("text/html") and "<script>" not in html and
          "&lt;script&gt;alert(1)&lt;/script&gt; &amp; co" in html and f">{v:.1f}</b> cm³" in html and
          "@media print" in html, "the report: the numbers, the caption escaped, print CSS")


def calibrate(api, measurements, out):
    doc = json.load(open(measurements))
    base = {"kind": "calibrate", "overrides": {"geometry.mesh_size": 0.012}, "measurements": doc}
    s, r = api.json("POST", "/api/jobs", {**base, "fit": "mu,zz"})
    check(s == 400 and "unknown parameter 'zz'" in r["error"], f"unknown fit name -> 400 ({r})")
    s, r = api.json("POST", "/api/jobs", {**base, "fit": "mu,rho"})
    check(s == 400 and "rho" in r["error"], f"an unidentifiable combination is refused ({r['error'][:60]}...)")
    s, r = api.json("POST", "/api/jobs", {**base, "fit": "mu,c", "max_evals": 12})
    live = follow_evaluations(api, r["id"])
    rec = api.wait(r["id"], ("done", "failed", "cancelled"), 600)
    check(rec["state"] == "done", f"calibration job done ({rec['state']}: {rec['error']})")
    p = rec["summary"]["parameters"]
    check([q["name"] for q in p] == ["mu", "c"] and all(q["interval_95"][0] < q["fitted"] < q["interval_95"][1] for q in p)
          and all(q["identifiability"] for q in p), "fitted parameters with 95 % intervals and identifiability in words")
    s, _, data = api.raw("GET", f"/api/jobs/{r['id']}/files/report.json")
    check(s == 200, "report.json served")
    report = json.loads(data)
    evaluations_channel(api, r["id"], rec, report, live)
    json.dump({"record": rec, "report": report}, open(out, "w"))


def follow_evaluations(api, job_id):
    """The evaluations of a running calibration as the page reads them (?since= the last one seen)."""
    live, states = [], set()
    end = time.time() + 600
    while time.time() < end:
        s, rec = api.json("GET", f"/api/jobs/{job_id}?since={live[-1]['n'] if live else 0}")
        assert s == 200, (s, rec)
        states.add(rec["state"])
        if rec["state"] == "running":
            live += rec["evaluations"]
        elif rec["state"] != "queued":
            return live
        time.sleep(0.2)
    raise AssertionError("calibration did not end")


def evaluations_channel(api, job_id, rec, report, live):
    """The API's evaluations of a finished calibration: the report's history, exactly; those read
    while it ran: the same evaluations to the 6 digits of the library's progress line."""
    s, full = api.json("GET", f"/api/jobs/{job_id}")
    ev, history = full["evaluations"], report["history"]
    check(s == 200 and len(ev) == report["evaluations"] == rec["summary"]["evaluations"] == len(history) > 0 and
          [e["n"] for e in ev] == list(range(1, len(ev) + 1)) and
          all(e["chi2"] == h["chi2"] and e["params"] == h["parameters"] and e["stage"] == h["stage"]
              for e, h in zip(ev, history)),
          f"the calibration's evaluations from the API: {len(ev)} = the report's, chi2 and parameters equal "
          f"to its history ({ev[0]['chi2']:.6g} -> {min(e['chi2'] for e in ev):.6g})")
    check(len(live) > 0 and [e["n"] for e in live] == list(range(1, len(live) + 1)) and
          all(abs(e["chi2"] / ev[e["n"] - 1]["chi2"] - 1) < 1e-5 and
              all(abs(v / ev[e["n"] - 1]["params"][k] - 1) < 1e-4 for k, v in e["params"].items())
              for e in live),
          f"while it ran: {len(live)} evaluations in order (?since=), chi2 within 1e-5 of the report's")
    s, after = api.json("GET", f"/api/jobs/{job_id}?since=5")
    check(s == 200 and [e["n"] for e in after["evaluations"]] == list(range(6, len(ev) + 1)),
          "?since=5: the evaluations after the 5th")
    for bad in ("-1", "x", "1e3", "%2e%2e", "99999999999"):
        s, err = api.json("GET", f"/api/jobs/{job_id}?since={bad}")
        check(s == 400 and "since" in err["error"], f"?since={bad} -> 400 ({err['error']})")


def failures(api):
    hard = {"geometry.mesh_size": 0.012, "postures.names": ["standing"], "solver.max_iterations": 1,
            "solver.min_load_step": 0.5}
    _, r = api.json("POST", "/api/jobs", {"kind": "simulate", "overrides": hard})
    rec = api.wait(r["id"], ("done", "failed", "cancelled"), 120)
    check(rec["state"] == "failed" and rec["error_kind"] == "solve" and "no convergence" in rec["error"],
          f"a failing solve: the job fails with the library's message ({rec['error'][:70]}...)")
    slow = {"geometry.mesh_size": 0.006, "postures.names": ["standing", "supine", "all_fours"]}
    _, r = api.json("POST", "/api/jobs", {"kind": "simulate", "overrides": slow})
    api.wait(r["id"], ("running",), 60)
    print(r["id"])  # server.sh kills this job's process


def crashed(api, job_id, folder):
    rec = api.wait(job_id, ("done", "failed", "cancelled"), 30)
    left = [f for f in os.listdir(folder) if ".partial-" in f]
    check(not left, f"its staging folder is removed ({left})")
    check(rec["state"] == "failed" and "signal 9" in rec["error"], f"a crashed job process: failed ({rec['error']})")
    s, _ = api.json("GET", "/api/keys")
    check(s == 200, "the server is still up")


def cancel(api):
    slow = {"geometry.mesh_size": 0.006, "postures.names": ["standing", "supine", "all_fours"]}
    _, a = api.json("POST", "/api/jobs", {"kind": "surgery", "overrides": slow})
    _, b = api.json("POST", "/api/jobs", {"kind": "simulate", "overrides": slow})
    api.wait(a["id"], ("running",), 60)
    s, rb = api.json("GET", f"/api/jobs/{b['id']}")
    check(rb["state"] == "queued", "one solve at a time: the second job waits")
    s, _ = api.json("POST", f"/api/jobs/{b['id']}/cancel", {})
    check(s == 200 and api.wait(b["id"], ("cancelled",), 5), "queued job cancelled")
    s, _ = api.json("POST", f"/api/jobs/{a['id']}/cancel", {})
    ra = api.wait(a["id"], ("cancelled", "done", "failed"), 30)
    check(s == 200 and ra["state"] == "cancelled", f"running job cancelled ({ra['state']})")
    s, _ = api.json("POST", f"/api/jobs/{a['id']}/cancel", {})
    check(s == 409, "cancelling a finished job -> 409")
    s, _, _ = api.raw("POST", f"/api/jobs/{b['id']}/cancel", "", {"Content-Type": "text/plain"})
    check(s == 415, "a cross-site form cannot post (cancel as text/plain -> 415)")
    print(json.dumps([a["id"], b["id"]]))


def parallel(api):
    slow = {"geometry.mesh_size": 0.006, "postures.names": ["standing", "supine", "all_fours"]}
    ids = [api.json("POST", "/api/jobs", {"kind": "simulate", "overrides": slow})[1]["id"] for _ in range(2)]
    both = False
    for _ in range(300):
        states = [api.json("GET", f"/api/jobs/{i}")[1]["state"] for i in ids]
        if states == ["running", "running"]:
            both = True
            break
        time.sleep(0.1)
    check(both, "--workers 2: two jobs run at the same time")
    for _ in range(100):
        s, _, log = api.raw("GET", f"/api/jobs/{ids[0]}/files/log.txt")
        if s == 200 and b"solving posture" in log:
            break
        time.sleep(0.1)
    check(s == 200 and b"solving posture" in log, "a running job's log is readable")
    for i in ids:
        api.json("POST", f"/api/jobs/{i}/cancel", {})
    check(all(api.wait(i, ("cancelled", "done"), 30) for i in ids), "both stopped")


def persisted(api, record_file):
    old = json.load(open(record_file))["record"]
    s, r = api.json("GET", f"/api/jobs/{old['id']}")
    check(s == 200 and r["state"] == "done" and r["summary"] == old["summary"],
          "finished job and its summary persist across a restart")
    s, _, _ = api.raw("GET", f"/api/jobs/{old['id']}/files/case.resolved.toml")
    check(s == 200, "its files are still served")


if __name__ == "__main__":
    api = Api(int(sys.argv[1]))
    phase = sys.argv[2]
    if phase == "refusals":
        refusals(api)
        sweep_refusals(api)
    elif phase == "plan":
        plan(api)
    elif phase == "clinic":
        clinic(api, sys.argv[3], sys.argv[4])
    elif phase == "surgery":
        surgery(api, sys.argv[3], sys.argv[4])
    elif phase == "calibrate":
        calibrate(api, sys.argv[3], sys.argv[4])
    elif phase == "failures":
        failures(api)
    elif phase == "crashed":
        crashed(api, sys.argv[3], sys.argv[4])
    elif phase == "cancel":
        cancel(api)
    elif phase == "parallel":
        parallel(api)
    elif phase == "persisted":
        persisted(api, sys.argv[3])
    else:
        sys.exit(f"unknown phase {phase}")
