#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""bench/truth/rescore.py on hand-made runs: a two-recording manifest, a
pseudo-true file and a summary.md table are rescored against the
pseudo-true value (outside the interval, and listed as borderline: the
table's rounding); two sets pool; a tether named as cables keeps its form;
a skin named with its upper-pole variation, read from a summary.json, is
covered only if both values lie inside both intervals; --benchmark refuses
a list that leaves a set out and reads a complete one; the table's cells
parse into intervals (a variation's interval in parentheses is not one).

Run: /usr/bin/python3 tests/truth/test_rescore.py SOURCE_DIR
"""
import json
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve() / "bench" / "truth"))

from rescore import benchmark_runs, parse_intervals, rescore, rescored  # noqa: E402

TABLE_HEAD = ("| recording | class | hidden | peak [mm] | named | q equivalent | q pseudo-true | "
              "fitted [95 % interval] | s |\n|---|---|---|---|---|---|---|---|---|\n")


def eff(candidate, parameter, value):
    return {"candidate": candidate, "q_equivalent": {"parameter": parameter, "value": value}}


def markdown_run_and_pool(d):
    """A markdown run rescored against a pseudo-true value, then pooled with a second set."""
    manifest = {"recordings": {
        "a": {"name": "a", "hidden": ["gland_core"], "hidden_label": "gland_core", "strength_class": "weak",
              "effects": [eff("gland_core", "gland.stiffness_ratio", 0.2)]},
        "c": {"name": "c", "hidden": [], "hidden_label": "none", "strength_class": "control", "effects": []}}}
    (d / "manifest.json").write_text(json.dumps(manifest))
    (d / "pseudo_true.json").write_text(json.dumps({"recordings": {"a": {"candidates": {
        "gland_core": {"value": 0.301}}}}}))
    (d / "summary.md").write_text(
        "text\n\n" + TABLE_HEAD
        + "| a | weak | gland_core | 1 | gland_core | 0.2 | - | 0.25 [0.22, 0.3] | 90.0 |\n"
        "| c | control | none | 0 | none | - | - | - | 40.0 |\n")
    s = rescore([(d / "manifest.json", d / "summary.md")])
    cov = s["rows"][0]["coverage"][0]
    assert cov["reference_kind"] == "pseudo-true" and cov["inside_reference"] is False, cov
    assert cov["inside"] is False and s["coverage_reference"]["pseudo_true_of"] == 1, s
    assert s["borderline"] == [("a", "gland_core")], s["borderline"]
    assert s["controls"] == {"false_discoveries": 0, "of": 1, "names": []}, s["controls"]
    pooled = d / "other"
    pooled.mkdir()
    (pooled / "manifest.json").write_text(json.dumps({"recordings": {"c2": {**manifest["recordings"]["c"],
                                                                             "name": "c2"}}}))
    (pooled / "summary.md").write_text(TABLE_HEAD + "| c2 | control | none | 0 | none | - | - | - | 50.0 |\n")
    both = rescore([(d / "manifest.json", d / "summary.md"), (pooled / "manifest.json", pooled / "summary.md")])
    assert both["controls"]["of"] == 2 and both["single_effect"]["of"] == 1, both["controls"]
    return pooled


def cable_form_kept():
    """A run before the forms column: a tether named as cables is counted under its physics."""
    cable = rescored({"name": "t", "named": ["suspensory_ligament"], "named_forms": ["suspensory_cables"],
                      "coverage": []}, {"hidden": ["suspensory_ligament"], "hidden_label": "suspensory_ligament",
                                        "strength_class": "weak", "effects": []}, {})
    assert cable["forms"] == {"suspensory_ligament": "suspensory_cables"}, cable


def skin_with_its_variation():
    """A skin named with its upper-pole variation, from summary.json: both intervals against both values."""
    skin_entry = {"hidden": ["skin"], "hidden_label": "skin", "strength_class": "strong",
                  "effects": [eff("skin", "skin.mu", 2500.0)]}
    check = lambda p, v, lo, hi: {"parameter": p, "fitted": v, "interval95": [lo, hi]}   # noqa: E731
    skin_row = {"name": "s", "named": ["skin"], "coverage": [{
        "candidate": "skin", "form": "skin+skin_upper_pole", **check("skin.mu", 2000.0, 1300.0, 3000.0),
        "extensions": [check("skin_upper_pole.mu", 2700.0, 1400.0, 5400.0)]}]}
    for upper, inside in ((3000.0, True), (6000.0, False)):
        record = {"candidates": {"skin": {"value": 2500.0}}, "other_forms": {"skin+skin_upper_pole": {
            "skin": {"parameter": "skin.mu", "value": 1900.0},
            "skin_upper_pole": {"parameter": "skin_upper_pole.mu", "value": upper}}}}
        cov = rescored(skin_row, skin_entry, record)["coverage"][0]
        assert cov["inside_reference"] is inside and cov["pseudo_true"] == 1900.0, cov


def benchmark_list(d, pooled):
    """--benchmark: a list that leaves a set out is refused; a complete one gives every set's run."""
    (d / "list.json").write_text(json.dumps({"folder": ".", "runs": {".": "summary.md"}}))
    try:
        benchmark_runs(d / "list.json", root=d)   # "other" has a manifest and no run
        raise AssertionError("a list that leaves a set out was accepted")
    except SystemExit as e:
        assert "no run of the set(s) other" in str(e), e
    (d / "list.json").write_text(json.dumps({"folder": ".", "runs": {".": "summary.md"},
                                             "apart": {"other": "scored by its own list"}}))
    assert benchmark_runs(d / "list.json", root=d) == [(d / "manifest.json", d / "summary.md")]
    (d / "list.json").write_text(json.dumps({"folder": ".", "runs": {".": "summary.md", "other": "other/summary.md"}}))
    assert benchmark_runs(d / "list.json", root=d) == [(d / "manifest.json", d / "summary.md"),
                                                      (pooled / "manifest.json", pooled / "summary.md")]


def table_cells():
    assert parse_intervals("1.2e-06 [9e-07, 2e-06]; 0.3 [-, 0.5]") == [(1.2e-6, 9e-7, 2e-6), (0.3, None, 0.5)]
    assert parse_intervals("2e+03 [1e+03, 3e+03] (skin_upper_pole.mu 3e+03 [1e+03, 5e+03])") == [(2e3, 1e3, 3e3)]


def main():
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        pooled = markdown_run_and_pool(d)
        cable_form_kept()
        skin_with_its_variation()
        benchmark_list(d, pooled)
        table_cells()
    print("rescore: OK")


if __name__ == "__main__":
    main()
