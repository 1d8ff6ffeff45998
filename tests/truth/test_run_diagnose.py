#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""bench/truth/run_diagnose.py with a fake breastsim and hand-made diagnoses.

The runner is driven end to end (main) with a fake binary that checks the
command line (the baseline's --set flags, P2 at 12 mm, --fit mu,lambda) and
writes a hand-made diagnosis.json per recording: a clean control, a control
with a false base_springs, a weak skin named with q inside its interval, a
gland named with an extra term and q outside (its pseudo-true value inside),
a pair named in full (its base_springs pseudo-true value outside). The
summary's counts (confusion matrix, exact verdicts, false discoveries and
rate, coverage against the equivalents and the pseudo-true values) must be
the expected ones. Then the scoring functions on hand-made rows: a tether
named in its cable form (that form's parameter and pseudo-true value, no
equivalent), a skin named with its upper-pole variation (covered only if
both values lie inside both intervals, no reference without the
variation's interval), a pair's references from the fit of the forms named,
the tally of forms named, and the forms' families as forms/model.py
declares them (needs UFL: /usr/bin/python3).

Run: /usr/bin/python3 tests/truth/test_run_diagnose.py SOURCE_DIR
"""
import json
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve() / "bench" / "truth"))

from run_diagnose import (CANDIDATES, coverage_rows, family_of_form, field_lines, field_row,  # noqa: E402
                          field_summary, form_tally, forms_of, main as run_diagnose_main,
                          pseudo_true_of_named, truth_forms)

# a fake breastsim: checks the command line and writes the answer of answers.json for the recording
FAKE_BINARY = r'''#!/usr/bin/env python3
import json, sys, pathlib
args = sys.argv[1:]
assert args[:2] == ["-q", "diagnose"], args
rec = json.loads(pathlib.Path(args[2]).read_text())
sets = [args[i + 1] for i, a in enumerate(args) if a == "--set"]
assert sets == ["base.fixed=true", "terms.base_springs=false", "terms.skin=false"], sets
assert args[args.index("--order") + 1] == "2" and args[args.index("--mesh-size") + 1] == "0.012"
assert args[args.index("--fit") + 1] == "mu,lambda"
out = pathlib.Path(args[args.index("--out") + 1]); out.mkdir(parents=True)
answers = json.loads(pathlib.Path(__file__).with_name("answers.json").read_text())
discovered, params = answers[rec["truth"]["name"]]
final = {"parameters": [{"name": "tissue.mu", "unit": "Pa", "value": 410.0, "interval95": [380.0, 440.0]}]
         + [{"name": n, "unit": "", "value": v, "interval95": iv} for n, v, iv in params],
         "chi2": 1.0, "dof": 1, "reduced_chi2": 1.0, "postures": []}
(out / "diagnosis.json").write_text(json.dumps({"format": "breastsim-diagnosis/1", "verdict": "fake",
    "discovered": discovered, "rounds": [], "final": final, "wall_time_s": 0.1}))
'''


def main():
    """Every check below adds to `bad` what it got wrong; the test fails if any did."""
    entries = {
        "c1": ([], []), "c2": ([], []),
        "s1": (["skin"], [("skin", "skin.mu", 2500.0)]),
        "g1": (["gland_core"], [("gland_core", "gland.excess", 1.5)]),
        "p1": (["base_springs", "gland_core"], [("base_springs", "base.compliance", 2e-7),
                                                ("gland_core", "gland.excess", 1.0)]),
    }
    answers = {"c1": [[], []], "c2": [["base_springs"], [["base.compliance", 1e-7, [1e-8, 1e-6]]]],
               "s1": [["skin"], [["skin.mu", 2600.0, [2000.0, 3000.0]]]],
               "g1": [["gland_core", "base_springs"], [["gland.excess", 3.0, [2.0, 4.0]],
                                                       ["base.compliance", 1e-7, [1e-8, 1e-6]]]],
               "p1": [["gland_core", "base_springs"], [["base.compliance", 2.1e-7, [1e-7, 4e-7]],
                                                       ["gland.excess", 1.1, [0.5, 2.0]]]]}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        (tmp / "recordings").mkdir()
        manifest = {"recordings": {}}
        for name, (hidden, qs) in entries.items():
            (tmp / "recordings" / f"{name}.json").write_text(json.dumps({"truth": {"name": name}}))
            cls = "control" if not hidden else ("pair" if len(hidden) == 2 else "weak")
            manifest["recordings"][name] = {
                "name": name, "file": f"recordings/{name}.json", "hidden": hidden,
                "hidden_label": "+".join(hidden) or "none", "strength_class": cls, "peak_change_mm": 1.0,
                "effects": [{"candidate": c, "q_equivalent": {"parameter": p, "value": v}} for c, p, v in qs]}
        (tmp / "manifest.json").write_text(json.dumps(manifest))
        pseudo = {"g1": {"gland_core": 3.5}, "p1": {"base_springs": 5e-7}}    # g1 inside, p1 outside
        (tmp / "pseudo_true.json").write_text(json.dumps({"recordings": {
            n: {"candidates": {c: {"value": v} for c, v in cs.items()}} for n, cs in pseudo.items()}}))
        build = tmp / "build"
        build.mkdir()
        (build / "breastsim").write_text(FAKE_BINARY)
        (build / "breastsim").chmod(0o755)
        (build / "answers.json").write_text(json.dumps(answers))
        run_diagnose_main([str(build), "--manifest", str(tmp / "manifest.json"), "--out", str(tmp / "out"),
                           "--nice", "-1"])
        s = json.loads((tmp / "out" / "summary.json").read_text())
    expect = {("controls", "false_discoveries"): 1, ("controls", "of"): 2,
              ("single_effect", "exact"): 1, ("single_effect", "of"): 2,
              ("single_effect", "named_hidden_with_extra"): 1, ("pairs", "exact"): 1,
              ("false_discovery_rate", "false_terms"): 2, ("false_discovery_rate", "named_terms"): 6,
              ("coverage", "inside"): 3, ("coverage", "of"): 4,
              ("coverage_reference", "inside"): 3, ("coverage_reference", "of"): 4,
              ("coverage_reference", "pseudo_true_inside"): 1, ("coverage_reference", "pseudo_true_of"): 2}
    bad = {k: (s[k[0]][k[1]], v) for k, v in expect.items() if s[k[0]][k[1]] != v}
    if s["confusion"]["none"] != {"base_springs": 1, "skin": 0, "suspensory_ligament": 0,
                                  "gland_core": 0, "none": 1}:
        bad["confusion.none"] = s["confusion"]["none"]
    # a tether named in its cable form: that form's parameter and pseudo-true value, no equivalent
    entry = {"effects": [{"candidate": "suspensory_ligament",
                          "q_equivalent": {"parameter": "ligament.k", "value": 2000.0, "approximate": True}}]}
    params = {"cables.k": {"value": 3000.0, "interval95": [2000.0, 4000.0]}}
    forms = {"suspensory_ligament": {"term": "suspensory_cables", "parameter": "cables.k"}}
    row = coverage_rows(entry, ["suspensory_ligament"], params, {}, forms)[0]
    if not (row["parameter"] == "cables.k" and row["inside"] is None and row["other_form"]):
        bad["other form without pseudo-true"] = row
    row = coverage_rows(entry, ["suspensory_ligament"], params, {"suspensory_cables": 3500.0}, forms)[0]
    if not (row["inside_reference"] is True and row["reference_kind"] == "pseudo-true" and not row["other_form"]):
        bad["other form with pseudo-true"] = row
    # a skin named with its upper-pole variation: the joint form, the base's parameter, no reference yet
    forms = forms_of([{"term": "skin_upper_pole", "physics": "skin", "parameter": "skin_upper_pole.mu",
                       "extends": "skin"},
                      {"term": "skin", "physics": "skin", "parameter": "skin.mu", "extends": ""}])
    entry = {"effects": [{"candidate": "skin", "q_equivalent": {"parameter": "skin.mu", "value": 2500.0}}]}
    params = {"skin.mu": {"value": 2400.0, "interval95": [2000.0, 3000.0]}}
    row = coverage_rows(entry, ["skin"], params, {"skin": 2600.0}, forms)[0]
    if not (row["form"] == "skin+skin_upper_pole" and row["parameter"] == "skin.mu"
            and row["inside_reference"] is None and row["other_form"]):
        bad["skin with its regional variation"] = row
    # ... with its pseudo-true values: covered only if the variation's value is inside its interval too
    params["skin_upper_pole.mu"] = {"value": 3000.0, "interval95": [1500.0, 6000.0]}
    joint = {"skin+skin_upper_pole": {"skin.mu": 2600.0, "skin_upper_pole.mu": 5000.0}}
    row = coverage_rows(entry, ["skin"], params, joint, forms)[0]
    if not (row["inside_reference"] is True and row["pseudo_true"] == 2600.0 and not row["other_form"]
            and row["extensions"][0]["inside"] is True):
        bad["skin with its regional variation, inside"] = row
    joint["skin+skin_upper_pole"]["skin_upper_pole.mu"] = 7000.0
    row = coverage_rows(entry, ["skin"], params, joint, forms)[0]
    if not (row["inside_reference"] is False and row["reference_kind"] == "pseudo-true"):
        bad["skin with its regional variation, the variation outside"] = row
    del params["skin_upper_pole.mu"]          # the variation's interval unknown: no reference
    row = coverage_rows(entry, ["skin"], params, joint, forms)[0]
    if not (row["inside_reference"] is None and row["other_form"]):
        bad["skin with its regional variation, its interval unknown"] = row
    # a pair's references come from the fit of the forms named: the springs' joint fit, or the cables'
    record = {"candidates": {"skin": {"value": 3000.0}, "suspensory_ligament": {"value": 4000.0}},
              "other_forms": {"suspensory_cables": {"skin": {"parameter": "skin.mu", "value": 2000.0},
                                                    "suspensory_cables": {"parameter": "cables.k", "value": 6000.0}}}}
    springs = pseudo_true_of_named(record, {"skin": {"term": "skin"},
                                            "suspensory_ligament": {"term": "suspensory_ligament"}})
    cables = pseudo_true_of_named(record, {"skin": {"term": "skin"},
                                           "suspensory_ligament": {"term": "suspensory_cables"}})
    if springs != {"skin": 3000.0, "suspensory_ligament": 4000.0} or (cables["skin"], cables["suspensory_cables"]) \
            != (2000.0, 6000.0):
        bad["pseudo-true of the forms named"] = (springs, cables)
    # forms: a cable truth named as cables, a spring truth named as cables, a false term not counted
    rows = [{"hidden": ["suspensory_ligament"], "forms": {"suspensory_ligament": "suspensory_cables"},
             "truth_forms": truth_forms({"effects": [{"candidate": "suspensory_ligament",
                                                      "pattern": {"variant": "cables"}}]})},
            {"hidden": ["suspensory_ligament"], "forms": {"suspensory_ligament": "suspensory_cables",
                                                          "skin": "skin"},
             "truth_forms": {"suspensory_ligament": "suspensory_ligament"}},
            {"hidden": ["gland_core"], "forms": {"gland_core": "gland_core"}, "truth_forms": {}}]
    tally = form_tally(rows)
    if tally != {"by_physics": {"suspensory_ligament": {"suspensory_cables": 2}, "gland_core": {"gland_core": 1}},
                 "truth_form_named": 1, "truth_form_known": 2}:
        bad["form tally"] = tally
    # every form's physics as the forms declare it: one of the physics this benchmark scores
    family = family_of_form()
    if (family.get("suspensory_cables") != "suspensory_ligament" or family.get("skin_upper_pole") != "skin"
            or not set(family.values()) <= set(CANDIDATES)):
        bad["family of form"] = family
    # the stiffness field: its row (location error, chi2/dof) and the summary over rows
    entry = {"effects": [{"derived": {"centre_m": [0.02, 0.015, -0.03]}}]}
    field = {"tried": True, "accepted": True, "family": "tissue_field", "likelihood_ratio": 400.0,
             "chi2_after": 1000.0, "dof_after": 1000, "summary": {"centroid_m": [0.023, 0.019, -0.03]}}
    fr = field_row(field, entry)
    if (abs(fr["location_error_mm"] - 5.0) > 1e-9 or abs(fr["chi2_dof_before"] - 1.4) > 1e-12
            or fr["chi2_dof_after"] != 1.0 or field_row({"tried": False}, entry) is not None):
        bad["field row"] = fr
    rejected = field_row({"tried": True, "accepted": False, "failed": ["LR"]}, {})
    fs = field_summary([{"field": fr}, {"field": rejected}, {"field": None}])
    if (fs["tried"], fs["modelled"], fs["location_error_mm"]["of"], fs["chi2_dof_after"]) != (2, 1, 1, 1.0) \
            or "modelled in 1 of 2" not in field_lines(fs)[0] or field_lines({"tried": 0}) != []:
        bad["field summary"] = fs
    if bad:
        print(f"test_run_diagnose: FAILED: {bad}")
        return 1
    print("run_diagnose: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
