#!/usr/bin/python3
"""Summarise bench/results.jsonl (medians over repeats) into docs/PERFORMANCE.md."""
import json
import statistics
import sys
from collections import defaultdict

rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
groups = defaultdict(list)
for r in rows:
    groups[r["label"]].append(r)

lines = ["| configuration | cells | unknowns | ranks | solver | median solve [s] | runs | "
         "median process [s] | peak RSS rank 0 [MB] | Newton | Krylov |",
         "|---|---|---|---|---|---|---|---|---|---|---|"]
for label, rs in groups.items():
    ok = [r for r in rs if not r.get("failed")]
    if not ok:
        t = [r["timeout_s"] for r in rs if "timeout_s" in r]
        lines.append(f"| {label} | {'timeout > %d s' % t[0] if t else 'failed'} | | | | | | | | | |")
        continue
    med = lambda k: statistics.median(r[k] for r in ok)
    r0 = ok[0]
    lines.append(f"| {label} | {r0['cells']} | {r0['unknowns']} | {r0['ranks']} | {r0['linear']} | "
                 f"{med('solve_s'):.2f} | {len(ok)} | {med('process_wall_s'):.2f} | "
                 f"{med('peak_rss_MB_rank0'):.0f} | {r0['newton']} | {r0['krylov']} |")

# Growth of the solve cost with the mesh (P1, direct, serial; and P1 amg).
growth = []
for lin in ("direct", "amg"):
    pts = [(groups[f"{s}_P1_{lin}_np1"], s) for s in ("5k", "50k", "200k") if f"{s}_P1_{lin}_np1" in groups]
    pts = [(statistics.median(r["solve_s"] for r in g if not r.get("failed")), g[0]["cells"], s)
           for g, s in pts if any(not r.get("failed") for r in g)]
    if len(pts) >= 2:
        import math
        (t0, n0, s0), (t1, n1, s1) = pts[0], pts[-1]
        growth.append(f"- P1 {lin}, serial: solve time grows as n^{math.log(t1 / t0) / math.log(n1 / n0):.2f} "
                      f"from {s0} ({n0} cells, {t0:.2f} s) to {s1} ({n1} cells, {t1:.2f} s).")

text = open(sys.argv[2]).read() if len(sys.argv) > 2 else ""
start, end = "<!-- bench:begin -->", "<!-- bench:end -->"
block = start + "\n" + "\n".join(lines) + "\n\n" + "\n".join(growth) + "\n" + end
if start in text:
    text = text[:text.index(start)] + block + text[text.index(end) + len(end):]
else:
    text += "\n" + block + "\n"
open(sys.argv[2], "w").write(text)
print("\n".join(lines + [""] + growth))
