# SPDX-License-Identifier: LGPL-3.0-or-later
"""The default-case surgery from the planning app against the CLI, same run.

Usage: app_surgery.py BREASTSIM CASE PORT WORK REPEATS
Alternates `breastsim surgery CASE` and the job the page starts
(POST /api/jobs with the page's overrides at their defaults), REPEATS times
each; the app's time is what the page waits: the POST until the job's record
reads done (polled every 50 ms). Prints one JSON line: the times, their
medians and the ratio app / CLI; checks that both give the same resected
volume.
"""
import http.client
import json
import os
import subprocess
import sys
import time

# The keys the page sends (app.js: CASE_FIELDS, the postures, SLIDERS).
PAGE_KEYS = ["geometry.R", "geometry.H", "geometry.mesh_size", "tissue.rho", "tissue.mu", "skin.mu",
             "postures.names", "incision.a_deg", "incision.s", "incision.h", "incision.d"]


def request(port, method, path, doc=None):
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    try:
        body = None if doc is None else json.dumps(doc)
        c.request(method, path, body, {"Content-Type": "application/json"} if body else {})
        r = c.getresponse()
        return r.status, json.loads(r.read())
    finally:
        c.close()


def page_overrides(port):
    status, keys = request(port, "GET", "/api/keys")
    assert status == 200, keys
    defaults = {k["key"]: k["default"] for k in keys["keys"]}
    return {k: defaults[k] for k in PAGE_KEYS}


def timed_job(port, doc):
    """POST the job, poll its record every 50 ms until it is no longer queued
    or running: the seconds the page waits and the finished record."""
    t0 = time.monotonic()
    status, r = request(port, "POST", "/api/jobs", doc)
    assert status == 202, r
    while True:
        status, job = request(port, "GET", f"/api/jobs/{r['id']}")
        if job["state"] not in ("queued", "running"):
            break
        time.sleep(0.05)
    seconds = time.monotonic() - t0
    assert job["state"] == "done", job
    return seconds, job


def app_run(port, overrides):
    seconds, job = timed_job(port, {"kind": "surgery", "overrides": overrides})
    return seconds, job["summary"]["resected_volume_cm3"]


def cli_run(program, case, out):
    t0 = time.monotonic()
    subprocess.run([program, "surgery", case, "--out", out], check=True, stdout=subprocess.DEVNULL)
    seconds = time.monotonic() - t0
    with open(os.path.join(out, "summary.json")) as f:
        return seconds, 1e6 * json.load(f)["resected_volume_m3"]


def main():
    program, case, port, work, repeats = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], int(sys.argv[5])
    overrides = page_overrides(port)
    cli, app, volumes = [], [], set()
    for i in range(repeats):
        t, v = cli_run(program, case, os.path.join(work, f"cli{i}"))
        cli.append(t)
        volumes.add(round(v, 6))
        t, v = app_run(port, overrides)
        app.append(t)
        volumes.add(round(v, 6))
    assert len(volumes) == 1, f"the CLI and the app resect different volumes: {volumes}"
    median = lambda xs: sorted(xs)[len(xs) // 2]
    print(json.dumps({"cli_s": [round(t, 2) for t in cli], "app_s": [round(t, 2) for t in app],
                      "cli_median_s": round(median(cli), 2), "app_median_s": round(median(app), 2),
                      "ratio": round(median(app) / median(cli), 3), "resected_volume_cm3": volumes.pop()}))


if __name__ == "__main__":
    main()
