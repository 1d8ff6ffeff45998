#!/usr/bin/env python3
"""Compare the verdicts of two runs of one benchmark set (run_diagnose.py
summary.json files), recording by recording, and apply the verdict-based
test of docs/DIAGNOSE.md ("Measured 2026-12-05, midday"): run B replaces
run A only if B has no false discovery on the controls, names no more
terms that are not hidden than A, and gives strictly more exact verdicts.
No differing verdict: inconclusive (A stays).

    python3 bench/truth/compare_runs.py --a all RUN_A/summary.json \
        --b largest-posture RUN_B/summary.json [--out FILE.md]
    python3 bench/truth/compare_runs.py --selftest

Only the standard library.
"""
import argparse
import json
import sys
import tempfile
from pathlib import Path


def rows_by_name(path):
    return {r["name"]: r for r in json.loads(Path(path).read_text())["rows"]}


def is_exact(row):
    return row["named"] is not None and sorted(row["named"]) == sorted(row["hidden"])


def false_terms(row):
    return len(set(row["named"] or []) - set(row["hidden"]))


def tally(rows):
    """Exact verdicts, false terms, and controls with a false discovery."""
    controls = [r for r in rows if not r["hidden"]]
    return {"exact": sum(map(is_exact, rows)), "of": len(rows),
            "false_terms": sum(map(false_terms, rows)),
            "controls_with_false_discovery": sum(1 for r in controls if r["named"]),
            "controls": len(controls), "failed": sum(1 for r in rows if r["named"] is None)}


def compare(a, b):
    """The test on the recordings both runs scored: per run its tally, the
    recordings whose verdicts differ, and the decision."""
    names = sorted(set(a) & set(b))
    ta, tb = tally([a[n] for n in names]), tally([b[n] for n in names])
    differ = [{"name": n, "hidden": a[n]["hidden"], "a": a[n]["named"], "b": b[n]["named"],
               "a_exact": is_exact(a[n]), "b_exact": is_exact(b[n])}
              for n in names if sorted(a[n]["named"] or []) != sorted(b[n]["named"] or [])
              or (a[n]["named"] is None) != (b[n]["named"] is None)]
    if not differ:
        decision = "inconclusive: no verdict differs (A stays)"
    elif (tb["controls_with_false_discovery"] == 0 and tb["false_terms"] <= ta["false_terms"]
          and tb["exact"] > ta["exact"]):
        decision = "B replaces A"
    else:
        decision = "A stays"
    return {"recordings": len(names), "only_in_one": sorted(set(a) ^ set(b)),
            "a": ta, "b": tb, "differ": differ, "decision": decision}


def label(named):
    return "failed" if named is None else ("+".join(sorted(named)) or "none")


def markdown(c, name_a, name_b):
    out = [f"# Verdicts compared: A = {name_a}, B = {name_b}", "",
           f"{c['recordings']} recordings scored in both runs"
           + (f"; only in one: {', '.join(c['only_in_one'])}" if c["only_in_one"] else "") + ".", "",
           "| run | exact verdicts | terms named that are not hidden | controls with a false discovery | failed |",
           "|---|---|---|---|---|"]
    for key, name in (("a", name_a), ("b", name_b)):
        t = c[key]
        out.append(f"| {key.upper()} = {name} | {t['exact']} / {t['of']} | {t['false_terms']} | "
                   f"{t['controls_with_false_discovery']} / {t['controls']} | {t['failed']} |")
    out += ["", "Recordings whose verdicts differ:", ""]
    if c["differ"]:
        out += ["| recording | hidden | A names | B names |", "|---|---|---|---|"]
        for d in c["differ"]:
            mark = lambda named, ok: label(named) + (" (exact)" if ok else "")
            out.append(f"| {d['name']} | {label(d['hidden'])} | {mark(d['a'], d['a_exact'])} | "
                       f"{mark(d['b'], d['b_exact'])} |")
    else:
        out.append("none.")
    out += ["", f"**Decision (the test written before the run): {c['decision']}.**", ""]
    return "\n".join(out)


def selftest():
    hidden = {"c1": [], "c2": [], "g1": ["gland_core"], "s1": ["skin"], "b1": ["base_springs"]}
    run_a = {"c1": [], "c2": [], "g1": [], "s1": ["skin"], "b1": ["base_springs"]}
    run_b = {"c1": [], "c2": [], "g1": ["gland_core"], "s1": ["skin"], "b1": ["base_springs"]}
    run_c = {"c1": ["base_springs"], "c2": [], "g1": ["gland_core"], "s1": ["skin"], "b1": ["base_springs"]}
    run_d = {"c1": [], "c2": [], "g1": ["gland_core"], "s1": ["skin", "gland_core"], "b1": None}

    def rows(named):
        return {n: {"name": n, "hidden": hidden[n], "named": v} for n, v in named.items()}
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "s.json"
        path.write_text(json.dumps({"rows": list(rows(run_a).values())}))
        assert rows_by_name(path) == rows(run_a)
    same = compare(rows(run_a), rows(run_a))
    assert same["decision"].startswith("inconclusive") and not same["differ"], same
    better = compare(rows(run_a), rows(run_b))
    assert better["decision"] == "B replaces A", better
    assert [d["name"] for d in better["differ"]] == ["g1"] and better["b"]["exact"] == 5
    fd = compare(rows(run_a), rows(run_c))    # more exact singles, but a control gains a term
    assert fd["decision"] == "A stays" and fd["b"]["controls_with_false_discovery"] == 1, fd
    worse = compare(rows(run_a), rows(run_d))  # an extra term and a failed run
    assert worse["decision"] == "A stays" and worse["b"]["false_terms"] == 1 and worse["b"]["failed"] == 1
    assert "| g1 | gland_core | none | gland_core (exact) |" in markdown(better, "all", "largest")
    print("compare_runs selftest: OK")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--a", nargs=2, metavar=("NAME", "SUMMARY_JSON"), help="the run in force")
    ap.add_argument("--b", nargs=2, metavar=("NAME", "SUMMARY_JSON"), help="the run tested against it")
    ap.add_argument("--out", help="write the markdown here as well")
    ap.add_argument("--selftest", action="store_true")
    a = ap.parse_args(argv)
    if a.selftest:
        selftest()
        return 0
    if not (a.a and a.b):
        ap.error("--a NAME SUMMARY_JSON and --b NAME SUMMARY_JSON are required")
    for name, path in (a.a, a.b):
        if not Path(path).is_file():
            ap.error(f"{name}: no summary file {path}")
    text = markdown(compare(rows_by_name(a.a[1]), rows_by_name(a.b[1])), a.a[0], a.b[0])
    print(text)
    if a.out:
        Path(a.out).write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
