#!/usr/bin/env python3
"""How much of each hidden effect the diagnosis can see.

For every single-effect recording with a pseudo-true value: the RMS change
of the skin the hidden effect makes at the truth's own material
(pseudo_true.json, `effect_rms_mm`: the truth with and without the effect),
against the RMS change the candidate of that physics adds in its first
refit, once the tissue's mu and lambda are refitted with and without it
(diagnosis.json, round 1, the refit of that physics with the largest LR:
`effect_rms_mm_all`). Their ratio is the visible share: the rest is taken
up by a stiffer or softer tissue. Whether the recording was named exactly
is listed beside it, and per candidate and class the range of the term's
effect over the recordings named and missed.

    python3 bench/truth/visible_effect.py --run MANIFEST RUN_DIR [--run ...] [--out FILE.md]
    python3 bench/truth/visible_effect.py --selftest

RUN_DIR holds run_diagnose.py's NAME/diagnosis/diagnosis.json. Only the
standard library (and run_diagnose.py's reader of pseudo_true.json).
"""
import argparse
import json
import statistics
import sys
import tempfile
from pathlib import Path

from run_diagnose import check_runs, emit, pseudo_true_recordings


def term_effect(dia, physics):
    """(effect RMS [mm], LR) of the round-1 refit of `physics` with the largest LR, or None."""
    rounds = dia.get("rounds", [])
    refits = [e for e in (rounds[0].get("evidence", []) if rounds else [])
              if e.get("physics", e["candidate"]) == physics]
    if not refits:
        return None
    best = max(refits, key=lambda e: e["likelihood_ratio"])
    return best["effect_rms_mm_all"], best["likelihood_ratio"]


def rows_of_run(manifest_path, run_dir):
    """One row per single-effect recording of the run that has a pseudo-true
    effect and a diagnosis."""
    manifest_path, run_dir = Path(manifest_path), Path(run_dir)
    recordings = json.loads(manifest_path.read_text())["recordings"]
    pseudo = pseudo_true_recordings(manifest_path.parent)
    rows = []
    for name, entry in sorted(recordings.items()):
        dj = run_dir / name / "diagnosis" / "diagnosis.json"
        if len(entry["hidden"]) != 1 or not dj.exists():
            continue
        physics = entry["hidden"][0]
        truth = pseudo.get(name, {}).get("candidates", {}).get(physics, {}).get("effect_rms_mm")
        if truth is None:
            continue
        dia = json.loads(dj.read_text())
        seen = term_effect(dia, physics)
        named = sorted(dia.get("discovered_physics", dia.get("discovered", []))) == [physics]
        rows.append({"name": name, "physics": physics, "class": entry["strength_class"],
                     "truth_mm": truth, "term_mm": seen[0] if seen else 0.0,
                     "lr": seen[1] if seen else 0.0, "named": named})
    return rows


def span(values, digits=3):
    return f"{min(values):.{digits}f}-{max(values):.{digits}f}" if values else "-"


def markdown(rows):
    out = ["| recording | physics | class | hidden effect RMS [mm] | term's effect RMS [mm] | visible share | LR | named exactly |",
           "|---|---|---|---|---|---|---|---|"]
    for r in sorted(rows, key=lambda r: (r["physics"], r["class"], r["term_mm"])):
        out.append(f"| {r['name']} | {r['physics']} | {r['class']} | {r['truth_mm']:.3f} | {r['term_mm']:.3f} | "
                   f"{r['term_mm'] / r['truth_mm']:.2f} | {r['lr']:.0f} | {'yes' if r['named'] else 'no'} |")
    out += ["", "| physics | class | recordings | visible share (median, range) | term's effect, named | term's effect, missed |",
            "|---|---|---|---|---|---|"]
    groups = sorted({(r["physics"], r["class"]) for r in rows})
    for physics, cls in groups:
        g = [r for r in rows if (r["physics"], r["class"]) == (physics, cls)]
        shares = [r["term_mm"] / r["truth_mm"] for r in g]
        out.append(f"| {physics} | {cls} | {len(g)} | {statistics.median(shares):.2f} ({span(shares, 2)}) | "
                   f"{span([r['term_mm'] for r in g if r['named']])} | "
                   f"{span([r['term_mm'] for r in g if not r['named']])} |")
    return "\n".join(out) + "\n"


def selftest():
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        manifest = {"recordings": {
            "g1": {"hidden": ["gland_core"], "strength_class": "weak"},
            "g2": {"hidden": ["gland_core"], "strength_class": "weak"},
            "p1": {"hidden": ["gland_core", "skin"], "strength_class": "pair"},
            "c1": {"hidden": [], "strength_class": "control"}}}
        (d / "manifest.json").write_text(json.dumps(manifest))
        (d / "pseudo_true.json").write_text(json.dumps({"recordings": {
            "g1": {"candidates": {"gland_core": {"effect_rms_mm": 0.25}}},
            "g2": {"candidates": {"gland_core": {"effect_rms_mm": 0.30}}}}}))

        def diagnosis(name, evidence, physics):
            (d / "run" / name / "diagnosis").mkdir(parents=True)
            (d / "run" / name / "diagnosis" / "diagnosis.json").write_text(json.dumps(
                {"rounds": [{"evidence": evidence}], "discovered_physics": physics}))
        ev = lambda c, eff, lr, phys=None: {"candidate": c, "physics": phys or c,
                                            "effect_rms_mm_all": eff, "likelihood_ratio": lr}
        diagnosis("g1", [ev("gland_core", 0.056, 99), ev("base_springs", 0.04, 30)], [])
        diagnosis("g2", [ev("gland_core", 0.10, 300)], ["gland_core"])
        diagnosis("c1", [], [])
        rows = rows_of_run(d / "manifest.json", d / "run")
        assert [r["name"] for r in rows] == ["g1", "g2"], rows          # singles with a pseudo-true effect
        assert rows[0]["term_mm"] == 0.056 and not rows[0]["named"] and rows[1]["named"]
        text = markdown(rows)
        assert "| g1 | gland_core | weak | 0.250 | 0.056 | 0.22 | 99 | no |" in text, text
        assert "| gland_core | weak | 2 | 0.28 (0.22-0.33) | 0.100-0.100 | 0.056-0.056 |" in text, text
        cables = {"rounds": [{"evidence": [ev("suspensory_cables", 0.09, 200, "suspensory_ligament"),
                                           ev("suspensory_ligament", 0.08, 150)]}]}
        assert term_effect(cables, "suspensory_ligament") == (0.09, 200)  # the form with the largest LR
        assert term_effect({"rounds": []}, "skin") is None
    print("visible_effect selftest: OK")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--run", nargs=2, action="append", default=[], metavar=("MANIFEST", "RUN_DIR"))
    ap.add_argument("--out", help="write the markdown here as well")
    ap.add_argument("--selftest", action="store_true")
    a = ap.parse_args(argv)
    if a.selftest:
        selftest()
        return 0
    check_runs(ap, a.run)
    rows = [r for manifest, run_dir in a.run for r in rows_of_run(manifest, run_dir)]
    emit(markdown(rows), a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
