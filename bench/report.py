#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Summarise bench/results.jsonl (medians over repeats) into docs/PERFORMANCE.md."""
import json
import statistics
import sys
from collections import defaultdict

rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
groups = defaultdict(list)
for r in rows:
    groups[r["label"]].append(r)

def coarse_column(r):
    """Unknowns and Newton iterations of each level of the coarse start,
    coarse first (older results: the coarse P1 level only)."""
    unknowns = r.get("level_unknowns", [r["coarse_unknowns"]])
    newton = r.get("level_newton", [r["coarse_newton"]])
    return " -> ".join(f"{u}: {n}" for u, n in zip(unknowns, newton)) + " |"


lines = ["| configuration | cells | unknowns | ranks | solver | median solve [s] | runs | "
         "median process [s] | peak RSS rank 0 [MB] | Newton | Krylov | coarse start: unknowns: Newton per level |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|"]
for label, rs in groups.items():
    ok = [r for r in rs if not r.get("failed")]
    if not ok:
        t = [r["timeout_s"] for r in rs if "timeout_s" in r]
        lines.append(f"| {label} | {'timeout > %d s' % t[0] if t else 'failed'} | | | | | | | | | | |")
        continue
    med = lambda k: statistics.median(r[k] for r in ok)
    r0 = ok[0]
    lines.append(f"| {label} | {r0['cells']} | {r0['unknowns']} | {r0['ranks']} | {r0['linear']} | "
                 f"{med('solve_s'):.2f} | {len(ok)} | {med('process_wall_s'):.2f} | "
                 f"{med('peak_rss_MB_rank0'):.0f} | {r0['newton']} | {r0['krylov']} | "
                 + (coarse_column(r0) if r0.get("coarse_unknowns") else "- |"))

# Growth of the solve cost with the mesh (serial), between consecutive sizes
# and over the whole range, for every order and solver measured.
import math
growth = []
for order in (1, 2):
    for lin in ("direct", "amg"):
        pts = []
        for s in ("5k", "50k", "200k"):
            ok = [r for r in groups.get(f"{s}_P{order}_{lin}_np1", []) if not r.get("failed")]
            if ok:
                pts.append((statistics.median(r["solve_s"] for r in ok), ok[0]["cells"], s))
        if len(pts) < 2:
            continue
        pairs = list(zip(pts, pts[1:])) + ([(pts[0], pts[-1])] if len(pts) > 2 else [])
        parts = [f"{a[2]} -> {b[2]}: n^{math.log(b[0] / a[0]) / math.log(b[1] / a[1]):.2f}"
                 for a, b in pairs]
        growth.append(f"- P{order} {lin}, serial: solve time grows as " + ", ".join(parts) + " ("
                      + ", ".join(f"{s} {n} cells {t:.2f} s" for t, n, s in pts) + ").")

text = open(sys.argv[2]).read() if len(sys.argv) > 2 else ""
start, end = "<!-- bench:begin -->", "<!-- bench:end -->"
block = start + "\n" + "\n".join(lines) + "\n\n" + "\n".join(growth) + "\n" + end
if start in text:
    text = text[:text.index(start)] + block + text[text.index(end) + len(end):]
else:
    text += "\n" + block + "\n"
open(sys.argv[2], "w").write(text)
print("\n".join(lines + [""] + growth))
