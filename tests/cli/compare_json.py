#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Compare the observables of two breastsim summary.json files.

Usage: compare_json.py A.json B.json RTOL ATOL
Every numeric observable of every posture must agree: |a - b| <= atol + rtol |b|.
Solver statistics (iterations, times) are not compared.
"""
import json
import sys

SKIP = {"newton_iterations", "linear_iterations", "wall_time_s", "load_steps", "failed_load_steps",
        "coarse_newton_iterations", "coarse_level_newton_iterations"}


def flatten(prefix, x, out):
    if isinstance(x, dict):
        for k, v in x.items():
            if k not in SKIP:
                flatten(f"{prefix}.{k}" if prefix else k, v, out)
    elif isinstance(x, list):
        for i, v in enumerate(x):
            flatten(f"{prefix}[{i}]", v, out)
    elif isinstance(x, (int, float)) and not isinstance(x, bool):
        out[prefix] = float(x)


a, b = (json.load(open(p)) for p in sys.argv[1:3])
rtol, atol = float(sys.argv[3]), float(sys.argv[4])
fa, fb = {}, {}
flatten("", a["postures"], fa)
flatten("", b["postures"], fb)
if fa.keys() != fb.keys():
    sys.exit(f"different observables: {sorted(set(fa) ^ set(fb))}")
bad = [(k, fa[k], fb[k]) for k in fa if abs(fa[k] - fb[k]) > atol + rtol * abs(fb[k])]
worst = max((abs(fa[k] - fb[k]) / (atol + rtol * abs(fb[k])), k) for k in fa)
print(f"compared {len(fa)} observables; worst ratio to tolerance {worst[0]:.3g} ({worst[1]})")
for k, x, y in bad:
    print(f"MISMATCH {k}: {x!r} vs {y!r}")
sys.exit(1 if bad else 0)
