#!/usr/bin/env python3
"""The evidence of every refitted candidate of one benchmark run, marked
genuine (the candidate is hidden in the truth) or spurious, from the
diagnosis.json files: the data for choosing a decision rule.

    python3 bench/truth/evidence_table.py [--manifest M] [--out RESULTS] [--sole-refusals]
    python3 bench/truth/evidence_table.py --selftest

Per refit (round, candidate): LR and its critical value, the margin
LR / critical, the misfit share LR / (chi2 - dof) of the model before it,
the effect RMS over all points, in the posture it changes most and at the
interval's end nearest the null [mm], the held-out postures' chi2 gains (their sum relative to LR, and how
many are positive), the refinement check's LR on the finer mesh and in the
continuum where made and whether it passed, accepted or not and why; how
many refits the refinement check met and refused. Then, for the accepted and
for the refused refits, the range of each measure over the genuine and the
spurious ones: a measure whose ranges do not overlap separates them.
Last, the refits that one rule alone refused (every other rule held), per
rule, genuine and spurious: what each rule carries, and what loosening it
would let through to the checks after it.
Only the standard library.
"""
import argparse
import json
import tempfile
from pathlib import Path

from run_diagnose import HERE

MEASURES = {
    "margin": lambda e: e["likelihood_ratio"] / e["critical_value"],
    "share": lambda e: e["likelihood_ratio"] / e["misfit_before"] if e.get("misfit_before", 0) > 0 else None,
    "effect_mm": lambda e: e["effect_rms_mm_all"],
    "posture_effect_mm": lambda e: e.get("effect_rms_mm_largest_posture", max(e.get("effect_rms_mm") or [0.0])),
    "edge_mm": lambda e: e["effect_at_null_edge_mm"],
    "held_out_over_lr": lambda e: sum(e["held_out_chi2_gain"]) / e["likelihood_ratio"]
    if e.get("held_out_chi2_gain") else None,
    "held_out_positive": lambda e: sum(g > 0 for g in e["held_out_chi2_gain"]) / len(e["held_out_chi2_gain"])
    if e.get("held_out_chi2_gain") else None,
    "fine_over_lr": lambda e: e["likelihood_ratio_fine"] / e["likelihood_ratio"]
    if e.get("likelihood_ratio_fine") else None,
}


def refits(manifest, out):
    """One row per refitted candidate: (recording, round, candidate, genuine,
    accepted, evidence) of every diagnosis.json under `out`."""
    for name, entry in sorted(manifest["recordings"].items()):
        path = out / name / "diagnosis" / "diagnosis.json"
        if not path.exists():
            continue
        dia = json.loads(path.read_text())
        hidden = set(entry.get("hidden", []))
        for k, rd in enumerate(dia.get("rounds", [])):
            for ev in rd.get("evidence", []):
                genuine = ev.get("physics", ev["candidate"]) in hidden  # a form of a hidden physics
                yield name, k + 1, ev["candidate"], genuine, bool(ev.get("accepted")), ev


def fmt(x):
    return "-" if x is None else f"{x:.3g}"


def ranges(rows):
    """{(accepted, genuine): {measure: (min, max, count)}}."""
    out = {}
    for _, _, _, genuine, accepted, ev in rows:
        group = out.setdefault((accepted, genuine), {})
        for m, f in MEASURES.items():
            v = f(ev)
            if v is None:
                continue
            lo, hi, n = group.get(m, (v, v, 0))
            group[m] = (min(lo, v), max(hi, v), n + 1)
    return out


def refinement_passed(ev):
    """The refinement check's outcome of one refit: True/False, None where
    it was not made (diagnosis.json refinement_passed, else from its LRs)."""
    if "likelihood_ratio_fine" not in ev:
        return None
    if "refinement_passed" in ev:
        return bool(ev["refinement_passed"])
    # runs before the split critical values held the full allowance in both
    return (ev["likelihood_ratio_fine"] > ev.get("critical_value_fine", ev["critical_value"])
            and ev["likelihood_ratio_continuum"] > ev.get("critical_value_continuum", ev["critical_value"]))


def refinement_counts(rows):
    """{genuine: (checked, refused)}: how many refits the refinement check
    met and how many it refused, for the genuine and the spurious ones."""
    out = {True: [0, 0], False: [0, 0]}
    for _, _, _, genuine, _, ev in rows:
        passed = refinement_passed(ev)
        if passed is not None:
            out[genuine][0] += 1
            out[genuine][1] += not passed
    return {g: tuple(v) for g, v in out.items()}


# The decision rules, recognised by how diagnosis.json's rejected_because
# words them (evidence.cpp); the first opening that matches names the rule.
RULE_OPENINGS = (
    ("its LR does not survive refinement", "refinement"),
    ("its LR ", "significance"),
    ("its effect, RMS", "effect"),
    ("its 95 % interval reaches the null", "effect_at_interval_end"),
    ("it does not improve the prediction", "held_out"),
    ("it improves the prediction of only", "held_out"),
    ("it explains ", "misfit_share"),
)


# The measure (MEASURES) each rule judges, shown beside a refit it refused alone.
RULE_MEASURE = {"significance": "margin", "effect": "effect_mm", "effect_at_interval_end": "edge_mm",
                "held_out": "held_out_positive", "misfit_share": "share", "refinement": "fine_over_lr"}


def rule_of(reason):
    """The rule a rejected_because sentence states, or 'other'."""
    return next((rule for opening, rule in RULE_OPENINGS if reason.startswith(opening)), "other")


def sole_refusals(rows):
    """{rule: [(recording, round, candidate, genuine, value)]} of the refits
    refused by that rule alone; value: the measure the rule judges (None if none)."""
    out = {}
    for name, rd, cand, genuine, accepted, ev in rows:
        reasons = ev.get("rejected_because", [])
        if not accepted and len(reasons) == 1:
            rule = rule_of(reasons[0])
            value = MEASURES[RULE_MEASURE[rule]](ev) if rule in RULE_MEASURE else None
            out.setdefault(rule, []).append((name, rd, cand, genuine, value))
    return out


def print_sole_refusals(rows):
    print("\n| rule (measure) | refused by it alone: genuine | spurious |")
    print("|---|---|---|")
    table = sole_refusals(rows)
    if not table:
        print("| (none) | - | - |")
    for rule, refused in sorted(table.items()):
        cell = lambda g: ", ".join(f"{n} r{rd} {c} ({fmt(v)})" for n, rd, c, gen, v in refused if gen == g) or "-"
        print(f"| {rule} ({RULE_MEASURE.get(rule, '-')}) | {cell(True)} | {cell(False)} |")


def print_tables(rows):
    print("| recording | round | candidate | genuine | accepted | LR | critical | "
          + " | ".join(MEASURES) + " | refinement | rejected because |")
    print("|---" * (7 + len(MEASURES)) + "|---|---|")
    for name, rd, cand, genuine, accepted, ev in rows:
        ref = {None: "-", True: "passed", False: "refused"}[refinement_passed(ev)]
        print(f"| {name} | {rd} | {cand} | {'yes' if genuine else 'no'} | {'yes' if accepted else 'no'} | "
              f"{ev['likelihood_ratio']:.1f} | {ev['critical_value']:.1f} | "
              + " | ".join(fmt(f(ev)) for f in MEASURES.values())
              + f" | {ref} | {'; '.join(ev.get('rejected_because', []))[:160]} |")
    counts = refinement_counts(rows)
    print("\nRefinement check: " + "; ".join(
        f"{label} refits: checked {counts[g][0]}, refused {counts[g][1]}"
        for g, label in ((True, "genuine"), (False, "spurious"))))
    print("\n| refits | " + " | ".join(MEASURES) + " |")
    print("|---" * (1 + len(MEASURES)) + "|")
    for (accepted, genuine), group in sorted(ranges(rows).items(), reverse=True):
        label = f"{'accepted' if accepted else 'refused'}, {'genuine' if genuine else 'spurious'}"
        cells = [f"{fmt(group[m][0])} - {fmt(group[m][1])} ({group[m][2]})" if m in group else "-"
                 for m in MEASURES]
        print(f"| {label} | " + " | ".join(cells) + " |")
    print_sole_refusals(rows)


def selftest():
    """Two refits of one recording whose truth hides the skin: the skin
    (genuine, accepted) and a ligament (spurious, refused)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        manifest = {"recordings": {"r": {"hidden": ["skin"]}}}
        skin = {"candidate": "skin", "accepted": True, "likelihood_ratio": 300.0, "critical_value": 30.0,
                "misfit_before": 400.0, "effect_rms_mm_all": 0.2, "effect_at_null_edge_mm": 0.18,
                "held_out_chi2_gain": [100.0, 50.0, -10.0, 10.0], "likelihood_ratio_fine": 270.0,
                "likelihood_ratio_continuum": 250.0}
        lig = {"candidate": "suspensory_ligament", "likelihood_ratio": 40.0, "critical_value": 30.0,
               "misfit_before": 400.0, "effect_rms_mm_all": 0.04, "effect_at_null_edge_mm": 0.03,
               "held_out_chi2_gain": [-5.0, 2.0, -1.0, -1.0], "rejected_because": ["its effect is small"]}
        (out / "r" / "diagnosis").mkdir(parents=True)
        (out / "r" / "diagnosis" / "diagnosis.json").write_text(json.dumps({"rounds": [{"evidence": [skin, lig]}]}))
        rows = list(refits(manifest, out))
        assert [(r[2], r[3], r[4]) for r in rows] == [("skin", True, True), ("suspensory_ligament", False, False)]
        got = ranges(rows)
        assert got[(True, True)]["margin"] == (10.0, 10.0, 1), got
        assert got[(True, True)]["share"] == (0.75, 0.75, 1), got
        assert got[(True, True)]["held_out_over_lr"] == (0.5, 0.5, 1), got
        assert got[(True, True)]["held_out_positive"] == (0.75, 0.75, 1), got
        assert got[(True, True)]["fine_over_lr"] == (0.9, 0.9, 1), got
        assert got[(False, False)]["held_out_over_lr"] == (-0.125, -0.125, 1), got
        assert "fine_over_lr" not in got[(False, False)], got
        assert refinement_counts(rows) == {True: (1, 0), False: (0, 0)}, refinement_counts(rows)
        assert rule_of("its LR 31.6 is below the critical value 47.3") == "significance"
        assert rule_of("its LR does not survive refinement: 175.0 on the finer mesh") == "refinement"
        assert rule_of("its 95 % interval reaches the null: at the interval's end") == "effect_at_interval_end"
        assert rule_of("it improves the prediction of only 2 of 4 held-out postures") == "held_out"
        assert rule_of("it explains 29 % of the misfit") == "misfit_share"
        assert rule_of("something new") == "other"
        assert sole_refusals(rows) == {"other": [("r", 1, "suspensory_ligament", False, None)]}, sole_refusals(rows)
        lone = dict(lig, rejected_because=["it explains 10 % of the misfit it is tested against"])
        got = sole_refusals([("r", 2, "suspensory_ligament", False, False, lone)])
        assert got == {"misfit_share": [("r", 2, "suspensory_ligament", False, 0.1)]}, got
        # a refused check, and a cable form of a hidden ligament counts as genuine
        cab = dict(lig, candidate="suspensory_cables", physics="suspensory_ligament",
                   likelihood_ratio_fine=20.0, likelihood_ratio_continuum=10.0,
                   critical_value_fine=30.0, critical_value_continuum=30.0)
        manifest["recordings"]["r"]["hidden"] = ["skin", "suspensory_ligament"]
        (out / "r" / "diagnosis" / "diagnosis.json").write_text(json.dumps({"rounds": [{"evidence": [skin, cab]}]}))
        rows = list(refits(manifest, out))
        assert [(r[2], r[3]) for r in rows] == [("skin", True), ("suspensory_cables", True)], rows
        assert refinement_counts(rows) == {True: (2, 1), False: (0, 0)}, refinement_counts(rows)
    print("evidence_table selftest: OK")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--manifest", default=str(HERE / "manifest.json"))
    ap.add_argument("--out", default=str(HERE / "results"))
    ap.add_argument("--sole-refusals", action="store_true",
                    help="print only the table of the refits one rule alone refused")
    ap.add_argument("--selftest", action="store_true", help="check the table on hand-made diagnoses")
    a = ap.parse_args()
    if a.selftest:
        return selftest()
    manifest = json.loads(Path(a.manifest).read_text())
    rows = list(refits(manifest, Path(a.out)))
    (print_sole_refusals if a.sole_refusals else print_tables)(rows)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
