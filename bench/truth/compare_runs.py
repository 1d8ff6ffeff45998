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


def classes(rows):
    """Controls, singles and pairs by the number of hidden effects."""
    return ([r for r in rows if not r["hidden"]], [r for r in rows if len(r["hidden"]) == 1],
            [r for r in rows if len(r["hidden"]) > 1])


def same_path(a, b):
    """Each run with the recordings scored only in the other taken from it."""
    return {**b, **a}, {**a, **b}


def no_harm(a, b, subset=()):
    """The test for a candidate added to the library (module docstring):
    its four conditions, each with the counts it compares, and the decision."""
    names = sorted(set(a) & set(b))
    ra, rb = [a[n] for n in names], [b[n] for n in names]
    (ca, sa, pa), (cb, sb, pb) = classes(ra), classes(rb)
    exact = lambda rows: sum(map(is_exact, rows))
    sub_a = [r for r in sa if r["name"] in subset]
    sub_b = [r for r in sb if r["name"] in subset]
    gained = [n for n in names if false_terms(b[n]) > false_terms(a[n])]
    conditions = [
        ("controls name no term in either run",
         f"A {sum(1 for r in ca if r['named'])} / {len(ca)}, B {sum(1 for r in cb if r['named'])} / {len(cb)}",
         not any(r["named"] for r in ca + cb)),
        ("pairs named exactly: B >= A", f"A {exact(pa)} / {len(pa)}, B {exact(pb)} / {len(pb)}",
         exact(pb) >= exact(pa)),
        ("singles named exactly: B >= A" + (", also on the subset" if subset else ""),
         f"A {exact(sa)} / {len(sa)}, B {exact(sb)} / {len(sb)}"
         + (f"; subset A {exact(sub_a)} / {len(sub_a)}, B {exact(sub_b)} / {len(sub_b)}" if subset else ""),
         exact(sb) >= exact(sa) and exact(sub_b) >= exact(sub_a)),
        ("no recording gains a term that is not hidden in B",
         ", ".join(gained) if gained else "none", not gained)]
    failed = [r for r in ra + rb if r["named"] is None]
    ok = all(c[2] for c in conditions) and not failed
    return {"recordings": len(names), "only_in_one": sorted(set(a) ^ set(b)), "conditions": conditions,
            "failed_runs": sorted({r["name"] for r in failed}),
            "decision": "B kept: every condition holds" if ok else "B not kept"}


def no_harm_markdown(t, name_a, name_b):
    out = [f"# Library change tested for harm: A = {name_a}, B = {name_b}", "",
           f"{t['recordings']} recordings scored in both runs"
           + (f"; only in one: {', '.join(t['only_in_one'])}" if t["only_in_one"] else "")
           + (f"; failed runs: {', '.join(t['failed_runs'])}" if t["failed_runs"] else "") + ".", "",
           "| condition | counts | holds |", "|---|---|---|"]
    out += [f"| {i}. {c} | {n} | {'yes' if ok else 'NO'} |" for i, (c, n, ok) in enumerate(t["conditions"], 1)]
    out += ["", f"**Decision: {t['decision']}.**", ""]
    return "\n".join(out)


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
    selftest_no_harm(rows, run_a, run_b, run_c)
    print("compare_runs selftest: OK")


def selftest_no_harm(rows, run_a, run_b, run_c):
    kept = no_harm(rows(run_a), rows(run_b), subset=("g1",))
    assert kept["decision"].startswith("B kept") and "subset A 0 / 1, B 1 / 1" in kept["conditions"][2][1]
    assert not no_harm(rows(run_a), rows(run_c))["conditions"][0][2]        # a control names a term
    lost = no_harm(rows(run_b), rows(run_a), subset=("g1",))                 # fewer singles exact
    assert lost["decision"] == "B not kept" and not lost["conditions"][2][2]
    extra = dict(run_a, s1=["skin", "gland_core"])
    gained = no_harm(rows(run_a), rows(extra))
    assert gained["conditions"][3][1] == "s1" and not gained["conditions"][3][2]
    part_a = {n: r for n, r in rows(run_a).items() if n != "c1"}             # c1 scored in B only
    assert no_harm(*same_path(part_a, rows(run_b)))["recordings"] == 5
    assert no_harm(part_a, rows(run_b))["only_in_one"] == ["c1"]
    assert "| 4. no recording gains" in no_harm_markdown(gained, "without", "with")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--a", nargs=2, metavar=("NAME", "SUMMARY_JSON"), help="the run in force")
    ap.add_argument("--b", nargs=2, metavar=("NAME", "SUMMARY_JSON"), help="the run tested against it")
    ap.add_argument("--out", help="write the markdown here as well")
    ap.add_argument("--test", choices=("verdicts", "no-harm"), default="verdicts",
                    help="verdicts: B replaces A only with strictly more exact verdicts; "
                         "no-harm: B (the library with an added candidate) is kept if it harms nothing")
    ap.add_argument("--subset", default="", help="no-harm: recordings whose singles are also compared alone")
    ap.add_argument("--same-path", action="store_true",
                    help="a recording scored in one run only is taken from it for the other")
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
    runs = rows_by_name(a.a[1]), rows_by_name(a.b[1])
    if a.same_path:
        runs = same_path(*runs)
    if a.test == "no-harm":
        subset = tuple(n for n in a.subset.split(",") if n)
        text = no_harm_markdown(no_harm(*runs, subset=subset), a.a[0], a.b[0])
    else:
        text = markdown(compare(*runs), a.a[0], a.b[0])
    print(text)
    if a.out:
        Path(a.out).write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
