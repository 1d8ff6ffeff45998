#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Score a committed benchmark run again against the pseudo-true values
computed since (pseudo_true.py's file beside the manifest), without
diagnosing again.

    python3 bench/truth/rescore.py --manifest bench/truth/chest_wall/manifest.json \
        --summary bench/truth/measured/main.json [--out FILE.json]
    python3 bench/truth/rescore.py --pool M1 S1 --pool M2 S2 ...   # several sets scored together
    python3 bench/truth/rescore.py --benchmark bench/truth/benchmark_runs.json   # every set, one run each

--summary is a run's summary.json (run_diagnose.py; full precision) or its
summary.md (the table's intervals are printed to 3 significant digits: a
reference value within ROUNDING of an interval end is counted as the table
says and listed as "borderline"). Prints the summary in run_diagnose.py's
format with the rescored coverage. --benchmark reads the run of each set
from a committed list and refuses a list that leaves out a set of its
folder (every manifest.json under it): the benchmark's figures are over
all the sets. Only the standard library.
"""
import argparse
import json
import re
import sys
from pathlib import Path

from run_diagnose import (HERE, coverage_rows, covered_effects, family_of_form, markdown, pseudo_true_of_named,
                          pseudo_true_recordings, summarize, truth_forms)

ROUNDING = 5e-3     # relative half-width of a 3-significant-digit number's last digit


def rows_from_json(path):
    return json.loads(path.read_text())["rows"]


def parse_intervals(text):
    """[(value, lo, hi)] of a table cell "v [lo, hi]; v [lo, hi]" ("-": []);
    a regional variation's interval in parentheses after its form's is not
    one of them."""
    number = r"([-+0-9.eE]+|-)"
    text = re.sub(r"\([^)]*\)", "", text)
    found = re.findall(number + r"\s*\[" + number + r",\s*" + number + r"\]", text)
    return [tuple(None if x == "-" else float(x) for x in f) for f in found]


def rows_from_markdown(path):
    """The rows of summary.md's per-recording table: name, class, named,
    seconds and the fitted intervals in the order of the named effects."""
    lines = path.read_text().splitlines()
    start = next(i for i, ln in enumerate(lines) if ln.startswith("| recording |"))
    header = [c.strip() for c in lines[start].strip("|").split("|")]
    rows = []
    for ln in lines[start + 2:]:
        if not ln.startswith("|"):
            break
        cell = dict(zip(header, (c.strip() for c in ln.strip("|").split("|"))))
        named, _, forms = cell["named"].partition(" (as ")   # the physics; "(as FORM+...)" names the forms
        row = {"name": cell["recording"], "class": cell["class"], "seconds": float(cell["s"]),
               "named": None if named == "failed" else ([] if named == "none" else sorted(named.split("+"))),
               "intervals": parse_intervals(cell["fitted [95 % interval]"])}
        if forms:
            row["named_forms"] = sorted(forms.rstrip(")").split("+"))
        rows.append(row)
    return rows


def rescored(row, entry, record):
    """`row` with hidden, peak and coverage from the manifest `entry` and the
    recording's pseudo_true.json entry `record`; a markdown row's intervals
    map to the named effects in manifest order (the order run_diagnose.py
    printed them in)."""
    out = {**row, "hidden": sorted(entry["hidden"]), "hidden_label": entry["hidden_label"],
           "class": entry["strength_class"], "peak_change_mm": entry.get("peak_change_mm")}
    if row["named"] is None:
        return {**out, "coverage": []}
    if "intervals" in row:
        effects = covered_effects(entry, row["named"])
        params = {e["q_equivalent"]["parameter"]: {"value": v, "interval95": [lo, hi]}
                  for e, (v, lo, hi) in zip(effects, row["intervals"])}
        forms = None
    else:   # every parameter of the named forms, their regional variations' too
        params = {x["parameter"]: {"value": x["fitted"], "interval95": x["interval95"]}
                  for c in row["coverage"] for x in [c, *c.get("extensions", [])]}
        forms = {c["candidate"]: {"term": c.get("form", c["candidate"]), "parameter": c["parameter"],
                                  "extension_parameters": [x["parameter"] for x in c.get("extensions", [])]}
                 for c in row["coverage"]}
    out["coverage"] = coverage_rows(entry, row["named"], params, pseudo_true_of_named(record, forms), forms)
    out["truth_forms"] = truth_forms(entry)
    if "forms" not in row:   # a run before the forms column: the forms it named, by their physics
        family = family_of_form()
        out["forms"] = {family.get(t, t): t for t in row.get("named_forms", row["named"])}
    return out


def borderline(rows):
    """(recording, candidate) whose reference lies within ROUNDING of an interval end."""
    near = lambda v, end: end is not None and v is not None and abs(v - end) <= ROUNDING * abs(end)
    return [(r["name"], c["candidate"]) for r in rows for c in r["coverage"]
            if near(c["reference"], c["interval95"][0]) or near(c["reference"], c["interval95"][1])]


def rescored_rows(manifest_path, summary_path):
    """The rows of one run, rescored against its set's pseudo-true values."""
    manifest = json.loads(manifest_path.read_text())["recordings"]
    records = pseudo_true_recordings(manifest_path.parent)
    source = rows_from_markdown if summary_path.suffix == ".md" else rows_from_json
    rows = []
    for row in source(summary_path):
        if row["name"] not in manifest:
            sys.exit(f"rescore.py: {row['name']} of {summary_path} is not in {manifest_path}")
        rows.append(rescored(row, manifest[row["name"]], records.get(row["name"], {})))
    return rows


def rescore(runs):
    """Summary over the runs [(manifest, summary)] together (names must differ)."""
    rows, near = [], []
    for manifest_path, summary_path in runs:
        part = rescored_rows(Path(manifest_path), Path(summary_path))
        rows += part
        near += borderline(part) if Path(summary_path).suffix == ".md" else []
    names = [r["name"] for r in rows]
    if len(set(names)) != len(names):
        sys.exit("rescore.py: the runs share recording names; pool only different sets")
    s = summarize(rows)
    s["borderline"] = near
    s["rows"] = rows
    return s


def benchmark_runs(path, root=HERE):
    """[(manifest, summary)] of every set of the benchmark list `path`:
    {"folder": F, "runs": {SET_FOLDER: SUMMARY}, "apart": {SET_FOLDER: WHY}},
    paths relative to root (bench/truth); every manifest.json under F must
    have a run, or be scored apart (a set with its own list, e.g. physics
    outside the candidate library)."""
    spec = json.loads(Path(path).read_text())
    folder = root / spec["folder"]
    sets = sorted(str(m.parent.relative_to(root)) for m in folder.rglob("manifest.json"))
    missing = [s for s in sets if s not in spec["runs"] and s not in spec.get("apart", {})]
    if missing:
        sys.exit(f"rescore.py: {path} has no run of the set(s) {', '.join(missing)}: the benchmark is every set")
    runs = []
    for set_folder, summary in sorted(spec["runs"].items()):
        manifest, summary = root / set_folder / "manifest.json", root / summary
        for f in (manifest, summary):
            if not f.is_file():
                sys.exit(f"rescore.py: {path}: no file {f}")
        runs.append((manifest, summary))
    return runs


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--manifest")
    ap.add_argument("--summary", help="a run's summary.json or summary.md")
    ap.add_argument("--pool", nargs=2, action="append", default=[], metavar=("MANIFEST", "SUMMARY"),
                    help="a further set's manifest and run, scored together with the others (repeatable)")
    ap.add_argument("--benchmark", help="a list of one run per set (benchmark_runs.json): every set pooled")
    ap.add_argument("--out", help="write the rescored summary (JSON) here")
    a = ap.parse_args(argv)
    if bool(a.manifest) != bool(a.summary) or not (a.manifest or a.pool or a.benchmark):
        ap.error("--manifest and --summary (or --pool MANIFEST SUMMARY, or --benchmark LIST) are required")
    runs = ([(a.manifest, a.summary)] if a.manifest else []) + [tuple(x) for x in a.pool]
    s = rescore(runs + (benchmark_runs(a.benchmark) if a.benchmark else []))
    command = "python3 bench/truth/rescore.py " + " ".join(argv if argv is not None else sys.argv[1:])
    print(markdown(s, s["rows"], command))
    if s["borderline"]:
        print("borderline (reference within rounding of an interval end): "
              + ", ".join(f"{n} {c}" for n, c in s["borderline"]))
    if a.out:
        Path(a.out).write_text(json.dumps(s, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
