#!/usr/bin/env python3
"""Two forms of one physics side by side: their round-1 evidence per recording.

For every recording of a run in which both forms A and B were refitted in
round 1 (diagnosis.json, `rounds[0].evidence`): each form's effect (RMS
change of the skin over all points once mu and lambda are refitted with and
without it, `effect_rms_mm_all`), its LR and critical value, and the ratios
B / A of effect and LR. Which form, if either, the diagnosis named is listed
beside them. The ratios' range over the recordings says whether the data
can tell the forms apart at all: near 1, the second form's shape is not
what the skin shows.

    python3 bench/truth/form_evidence.py --forms gland_core gland_lobe --run MANIFEST RUN_DIR [--run ...] [--out FILE.md]
    python3 bench/truth/form_evidence.py --selftest

RUN_DIR holds run_diagnose.py's NAME/diagnosis/diagnosis.json. Only the
standard library (and run_diagnose.py's check of the --run arguments).
"""
import argparse
import json
import sys
import tempfile
from pathlib import Path

from run_diagnose import check_runs, emit


def round_one_refit(dia, form):
    """The round-1 evidence entry of candidate `form`, or None."""
    rounds = dia.get("rounds", [])
    for e in rounds[0].get("evidence", []) if rounds else []:
        if e["candidate"] == form:
            return e
    return None


def rows_of_run(manifest_path, run_dir, form_a, form_b):
    """One row per recording of the run in which both forms were refitted in round 1."""
    recordings = json.loads(Path(manifest_path).read_text())["recordings"]
    rows = []
    for name, entry in sorted(recordings.items()):
        dj = Path(run_dir) / name / "diagnosis" / "diagnosis.json"
        if not dj.exists():
            continue
        dia = json.loads(dj.read_text())
        a, b = round_one_refit(dia, form_a), round_one_refit(dia, form_b)
        if a is None or b is None:
            continue
        named = [f for f in (form_a, form_b) if f in dia.get("discovered", [])]
        rows.append({"name": name, "hidden": "+".join(entry["hidden"]) or "none",
                     "effect_a": a["effect_rms_mm_all"], "effect_b": b["effect_rms_mm_all"],
                     "lr_a": a["likelihood_ratio"], "lr_b": b["likelihood_ratio"],
                     "crit_a": a["critical_value"], "crit_b": b["critical_value"],
                     "named": ",".join(named) or "neither"})
    return rows


def span(values):
    return f"{min(values):.2f}-{max(values):.2f}" if values else "-"


def quotient(b, a):
    """b / a to two decimals; "-" unless a > 0 (as the summary line's ranges)."""
    return f"{b / a:.2f}" if a > 0 else "-"


def markdown(rows, form_a, form_b):
    out = [f"| recording | hidden | effect {form_a} [mm] | effect {form_b} [mm] | effect B/A | "
           f"LR {form_a} (critical) | LR {form_b} (critical) | LR B/A | named |",
           "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['name']} | {r['hidden']} | {r['effect_a']:.3f} | {r['effect_b']:.3f} | "
                   f"{quotient(r['effect_b'], r['effect_a'])} | {r['lr_a']:.1f} ({r['crit_a']:.1f}) | "
                   f"{r['lr_b']:.1f} ({r['crit_b']:.1f}) | {quotient(r['lr_b'], r['lr_a'])} | {r['named']} |")
    effect = [r["effect_b"] / r["effect_a"] for r in rows if r["effect_a"] > 0]
    lr = [r["lr_b"] / r["lr_a"] for r in rows if r["lr_a"] > 0]
    out += ["", f"B = {form_b}, A = {form_a}: {len(rows)} recordings with both refitted in round 1; "
            f"effect B/A {span(effect)}, LR B/A {span(lr)}."]
    return "\n".join(out) + "\n"


def selftest():
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        (d / "manifest.json").write_text(json.dumps({"recordings": {
            "g1": {"hidden": ["gland_core"]}, "g2": {"hidden": ["gland_core"]},
            "c1": {"hidden": []}, "s1": {"hidden": ["skin"]}}}))
        ev = lambda c, eff, lr, crit: {"candidate": c, "effect_rms_mm_all": eff,
                                       "likelihood_ratio": lr, "critical_value": crit}

        def diagnosis(name, evidence, discovered):
            (d / "run" / name / "diagnosis").mkdir(parents=True)
            (d / "run" / name / "diagnosis" / "diagnosis.json").write_text(json.dumps(
                {"rounds": [{"evidence": evidence}, {"evidence": [ev("gland_lobe", 9, 9, 1)]}],
                 "discovered": discovered}))
        diagnosis("g1", [ev("gland_core", 0.10, 200, 20), ev("gland_lobe", 0.102, 210, 20)], ["gland_lobe"])
        diagnosis("g2", [ev("gland_core", 0.05, 100, 20), ev("gland_lobe", 0.049, 97, 20)], [])
        diagnosis("c1", [], [])
        diagnosis("s1", [ev("skin", 0.2, 500, 20), ev("gland_core", 0.04, 30, 20)], ["skin"])
        rows = rows_of_run(d / "manifest.json", d / "run", "gland_core", "gland_lobe")
        assert [r["name"] for r in rows] == ["g1", "g2"], rows   # both forms refitted in round 1 only
        assert rows[0]["named"] == "gland_lobe" and rows[1]["named"] == "neither"
        text = markdown(rows, "gland_core", "gland_lobe")
        assert "| g1 | gland_core | 0.100 | 0.102 | 1.02 | 200.0 (20.0) | 210.0 (20.0) | 1.05 | gland_lobe |" in text, text
        assert "effect B/A 0.98-1.02, LR B/A 0.97-1.05." in text, text
        assert round_one_refit({"rounds": []}, "skin") is None
    print("form_evidence selftest: OK")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--forms", nargs=2, metavar=("A", "B"), help="the two candidates compared (B / A)")
    ap.add_argument("--run", nargs=2, action="append", default=[], metavar=("MANIFEST", "RUN_DIR"))
    ap.add_argument("--out", help="write the markdown here as well")
    ap.add_argument("--selftest", action="store_true")
    a = ap.parse_args(argv)
    if a.selftest:
        selftest()
        return 0
    if not a.forms:
        ap.error("--forms A B is required")
    check_runs(ap, a.run)
    rows = [r for m, d in a.run for r in rows_of_run(m, d, *a.forms)]
    emit(markdown(rows, *a.forms), a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
