# SPDX-License-Identifier: LGPL-3.0-or-later
"""Summary of bench/diagnose_confusion.sh: confusion matrix (hidden -> named),
false-discovery rate on the controls, recovery of the hidden parameter
(inside the reported 95 % interval), RMS before/after, time per diagnosis.

Usage: python3 diagnose_report.py RESULTS_DIR CASE...
"""
import json
import statistics
import sys
from pathlib import Path


def main():
    root = Path(sys.argv[1])
    cases = sys.argv[2:]
    rows, named_set = [], set()
    for d in sorted(root.glob("*_*")):
        if not (d / "diagnosis" / "diagnosis.json").exists():
            continue
        hidden = d.name.rsplit("_", 1)[0]
        if hidden not in cases:
            continue
        rec = json.loads((d / "recording.json").read_text())
        dia = json.loads((d / "diagnosis" / "diagnosis.json").read_text())
        named = dia["discovered"][0] if dia["discovered"] else "none"
        named_set.add(named)
        inside = None
        if hidden != "control" and named == hidden:
            par = rec["truth"]["parameter"]
            p = next(q for q in dia["final"]["parameters"] if q["name"] == par)
            lo, hi = p["interval95"]
            inside = lo <= rec["truth"]["value"] <= hi
            fitted = p["value"]
        else:
            fitted = None
        first = dia["rounds"][0]["fit"]
        rms = lambda f: statistics.mean(q["rms_mm"] for q in f["postures"])
        rows.append(dict(hidden=hidden, seed=d.name.rsplit("_", 1)[1], named=named,
                         extra=dia["discovered"][1:], truth=rec["truth"]["value"], fitted=fitted,
                         inside=inside, rms_before=rms(first), rms_after=rms(dia["final"]),
                         chi2_after=dia["final"]["reduced_chi2"],
                         seconds=float((d / "seconds").read_text())))
    columns = [c for c in cases if c != "control"] + ["none"]
    columns += sorted(named_set - set(columns))
    lines = ["hidden \\ named       " + " ".join(f"{c:>20}" for c in columns)]
    matrix = {}
    for h in cases:
        counts = {c: sum(1 for r in rows if r["hidden"] == h and r["named"] == c) for c in columns}
        matrix[h] = counts
        lines.append(f"{h:<20} " + " ".join(f"{counts[c]:>20}" for c in columns))
    controls = [r for r in rows if r["hidden"] == "control"]
    fdr = sum(1 for r in controls if r["named"] != "none") / max(len(controls), 1)
    lines.append(f"\ncontrol false-discovery rate: {fdr:.2f} ({len(controls)} controls)")
    hits = [r for r in rows if r["inside"] is not None]
    lines.append(f"hidden value inside the reported 95 % interval: "
                 f"{sum(r['inside'] for r in hits)} of {len(hits)} correct discoveries")
    lines.append(f"time per diagnosis: median {statistics.median(r['seconds'] for r in rows):.1f} s "
                 f"(min {min(r['seconds'] for r in rows):.1f}, max {max(r['seconds'] for r in rows):.1f})")
    lines.append("\nhidden               seed named                truth      fitted     inside "
                 "RMS before/after [mm] chi2/dof after extra")
    for r in rows:
        lines.append(f"{r['hidden']:<20} {r['seed']:>4} {r['named']:<20} {r['truth']:<10.4g} "
                     f"{(r['fitted'] if r['fitted'] is not None else float('nan')):<10.4g} "
                     f"{str(r['inside']):<6} {r['rms_before']:.3f}/{r['rms_after']:.3f}          "
                     f"{r['chi2_after']:.3f}          {','.join(r['extra'])}")
    text = "\n".join(lines)
    print(text)
    (root / "confusion.json").write_text(json.dumps(dict(matrix=matrix, control_fdr=fdr, rows=rows), indent=1))
    (root / "confusion.txt").write_text(text + "\n")


if __name__ == "__main__":
    main()
