#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""The log-log plot of a `breastsim converge` result: relative error of each
quantity against its Richardson extrapolation, and the MMS errors, over the
relative mesh size.

Usage: convergence_plot.py CONVERGENCE_JSON PNG
"""
import json
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
d = json.load(open(sys.argv[1]))
fig, ax = plt.subplots(figsize=(7, 5))
for s in d.get("studies", []):
    hrel = [2.0 ** -l for l in s["refinements"]]
    for name, q in s["quantities"].items():
        ext = q["richardson"]
        if ext is None:
            continue
        err = [abs(v - ext) / max(abs(ext), 1e-300) for v in q["values"]]
        pts = [(h, e) for h, e in zip(hrel, err) if e > 0]
        if pts:
            ax.loglog(*zip(*pts), "o-", label=f"P{s['element_order']} {name} (p={q['observed_order']:.2f})")
for s in d.get("mms", []):
    hrel = [L["h_eff"] / s["levels"][0]["h_eff"] for L in s["levels"]]
    p = s.get("formulation", "") + f" P{s['element_order']}"
    ax.loglog(hrel, [L["relative_error_l2"] for L in s["levels"]], "s-", label=f"MMS {p} L2")
    ax.loglog(hrel, [L["relative_error_h1"] for L in s["levels"]], "^-", label=f"MMS {p} H1")
ax.set_xlabel("relative mesh size h / h0")
ax.set_ylabel("relative error (|q - q_Richardson| / |q_Richardson|, or MMS error)")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=7)
ax.set_title("breastsim converge")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
