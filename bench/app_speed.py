# SPDX-License-Identifier: LGPL-3.0-or-later
"""The planning app's surgery job and a 3 x 3 sweep job, a baseline server
against this one, alternating in the same run.

Usage: app_speed.py OLD_PORT NEW_PORT REPEATS
Each job is posted as the page posts it (the page's keys at their defaults;
the sweep varies a and s over three values each); its time is what the page
waits: the POST until the job's record reads done (polled every 50 ms).
Prints one JSON line: the times, their medians and the ratios old / new;
checks that both servers resect the same volumes.
"""
import json
import statistics
import sys

from app_surgery import page_overrides, timed_job

SWEEP = {"a": [25, 30, 35], "s": [0.015, 0.02, 0.025]}


def run(port, job):
    seconds, record = timed_job(port, job)
    summary = record["summary"]
    volumes = ([round(row["resected_volume_cm3"], 4) for row in summary["rows"]]
               if job["kind"] == "sweep" else [round(summary["resected_volume_cm3"], 4)])
    return seconds, volumes


def main():
    ports = {"old": int(sys.argv[1]), "new": int(sys.argv[2])}
    repeats = int(sys.argv[3])
    jobs = {"surgery": {"kind": "surgery", "overrides": page_overrides(ports["new"])}}
    jobs["sweep"] = {"kind": "sweep", "overrides": jobs["surgery"]["overrides"], "vary": SWEEP}
    times = {(k, w): [] for k in jobs for w in ports}
    volumes = {}
    for _ in range(repeats):
        for kind, job in jobs.items():
            for which, port in ports.items():
                t, v = run(port, job)
                times[(kind, which)].append(round(t, 2))
                volumes.setdefault(kind, {})[which] = v
    out = {}
    for kind in jobs:
        old, new = (statistics.median(times[(kind, w)]) for w in ("old", "new"))
        assert volumes[kind]["old"] == volumes[kind]["new"], f"{kind}: the servers resect {volumes[kind]}"
        out[kind] = {"old_s": times[(kind, "old")], "new_s": times[(kind, "new")], "old_median_s": old,
                     "new_median_s": new, "ratio_old_new": round(old / new, 2),
                     "resected_volume_cm3": volumes[kind]["new"]}
    print(json.dumps(out))


main()
