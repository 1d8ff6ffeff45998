#!/usr/bin/env python3
"""The evidence of every refitted candidate of one benchmark run, marked
genuine (the candidate is hidden in the truth) or spurious, from the
diagnosis.json files: the data for choosing a decision rule.

    python3 bench/truth/evidence_table.py [--manifest M] [--out RESULTS]
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
    ap.add_argument("--selftest", action="store_true", help="check the table on hand-made diagnoses")
    a = ap.parse_args()
    if a.selftest:
        return selftest()
    manifest = json.loads(Path(a.manifest).read_text())
    print_tables(list(refits(manifest, Path(a.out))))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
