#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Run `breastsim diagnose` on the independent-truth recordings and score it.

    python3 bench/truth/run_diagnose.py BUILD_DIR [--only NAME,...] [--classes control,weak,...]
                                        [--limit N] [--out DIR] [--rerun] [--summarize-only]
                                        [--jobs N] [--mpi N [--ranks-per-case K]]

Every recording of bench/truth/manifest.json (or the selected subset) is
diagnosed with the benchmark's baseline: tissue eq. (5), fixed base, no skin,
R, H and rho known (from the recording), `--fit mu,lambda`, on the
diagnosis discretisation of docs/DIAGNOSE.md (P2 at 12 mm):

    nice -n 19 BUILD/breastsim -q diagnose REC --case cases/default.toml \
        --set base.fixed=true --set terms.base_springs=false --set terms.skin=false \
        --order 2 --mesh-size 0.012 --fit mu,lambda --out OUT/NAME/diagnosis [EXTRA]

(`--order 2 --mesh-size 0.012` is diagnose's default, written out; EXTRA
comes last: `--extra "--order 0 --mesh-size 0"` diagnoses on the case's P1
mesh instead.)

Resumable: a recording whose OUT/NAME/diagnosis/diagnosis.json exists is not
run again (unless --rerun). Writes OUT/summary.json and OUT/summary.md:
confusion matrix (hidden -> named), exact verdicts on single-effect
recordings, false discoveries on the controls, false-discovery rate,
coverage of the hidden value q by the reported 95 % interval, time per
diagnosis. Running and scoring need only the standard library; rescoring
runs older than their "forms" field (and tests/truth/test_run_diagnose.py)
read the candidates' families from forms/model.py, and so need UFL
(/usr/bin/python3).
"""
import argparse
import concurrent.futures
import functools
import json
import math
import os
import shlex
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
CANDIDATES = ["base_springs", "skin", "suspensory_ligament", "gland_core"]
# the candidate form of each truth variant a generator effect names (its pattern's "variant")
FORM_OF_VARIANT = {"springs": "suspensory_ligament", "cables": "suspensory_cables"}
BASELINE_SETS = ["base.fixed=true", "terms.base_springs=false", "terms.skin=false"]
# the diagnosis discretisation: P2 with its curved skin at 12 mm (docs/DIAGNOSE.md)
DISCRETISATION = ["--order", "2", "--mesh-size", "0.012"]
FIT = "mu,lambda"
# the benchmark's targets
TARGET_EXACT, TARGET_COVERAGE, TARGET_MEDIAN_S, MIN_CONTROLS = 0.95, 0.90, 120.0, 12


# -- running ---------------------------------------------------------------------
def diagnose_command(binary, recording, out_dir, case, extra, nice, mpi=None):
    """mpi = (ranks, ranks per case): mpirun -n ranks ... --ranks-per-case K."""
    cmd = ["nice", "-n", str(nice)] if nice is not None else []
    if mpi:
        cmd += ["mpirun", "-n", str(mpi[0])]
    cmd += [str(binary), "-q", "diagnose", str(recording), "--case", str(case)]
    for s in BASELINE_SETS:
        cmd += ["--set", s]
    cmd += DISCRETISATION
    cmd += ["--fit", FIT, "--out", str(out_dir)] + list(extra)
    if mpi:
        cmd += ["--ranks-per-case", str(mpi[1])]
    return cmd


MPI_ROOT_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                "OMPI_MCA_rmaps_base_oversubscribe": "1"}


def run_one(binary, manifest_dir, entry, out, case, extra, nice, rerun, mpi=None):
    """Diagnose one recording into OUT/NAME/; returns 'ran', 'skipped' or 'failed'."""
    d = out / entry["name"]
    if (d / "diagnosis" / "diagnosis.json").exists() and not rerun:
        return "skipped"
    d.mkdir(parents=True, exist_ok=True)
    rec = manifest_dir / entry["file"]
    cmd = diagnose_command(binary, rec, d / "diagnosis", case, extra, nice, mpi)
    (d / "command.txt").write_text(shlex.join(cmd) + "\n")
    t0 = time.monotonic()
    with open(d / "diagnose.log", "w") as log:
        env = dict(os.environ, **MPI_ROOT_ENV) if mpi else None
        rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
    seconds = time.monotonic() - t0
    (d / "run.json").write_text(json.dumps({"exit_code": rc, "seconds": seconds,
                                            "command": cmd}, indent=1) + "\n")
    return "ran" if rc == 0 else "failed"


# -- scoring ---------------------------------------------------------------------
def pseudo_true_recordings(manifest_dir):
    """The recordings of pseudo_true.py's output beside the manifest, {} if absent."""
    path = manifest_dir / "pseudo_true.json"
    return json.loads(path.read_text())["recordings"] if path.exists() else {}


def pseudo_true_of_named(record, forms):
    """{candidate or form: q*} of a recording's pseudo_true.json entry for
    the forms the diagnosis named (`forms` {physics: {"term"}}): the
    candidates' joint fit, except where an alternative form was named that
    has a fit of its own (pseudo_true.py --form, "other_forms"): that
    form's value, and when it is the only one, that joint fit's values of
    the other candidates too. A form with regional variations
    ("skin+skin_upper_pole") maps to {parameter: q*}, one per term."""
    out = {c: v["value"] for c, v in (record or {}).get("candidates", {}).items()}
    fits = (record or {}).get("other_forms", {})
    named = [f["term"] for f in (forms or {}).values() if f["term"] in fits]
    for name in named:
        own = name.split("+")
        fit = fits[name]
        out[name] = ({fit[t]["parameter"]: fit[t]["value"] for t in own} if len(own) > 1
                     else fit[name]["value"])
        if len(named) == 1:
            out.update({t: v["value"] for t, v in fit.items() if t not in own})
    return out


def read_result(out, entry, record=None):
    """One row: hidden, named, intervals, time; None when not run yet. The
    reference q of a discovery is its pseudo-true value where pseudo_true.py
    computed one (`record`: the recording's pseudo_true.json entry, read
    by pseudo_true_of_named), else the manifest's equivalent."""
    d = out / entry["name"]
    run = d / "run.json"
    if not run.exists():
        return None
    info = json.loads(run.read_text())
    row = {"name": entry["name"], "hidden": sorted(entry["hidden"]),
           "hidden_label": entry["hidden_label"], "class": entry["strength_class"],
           "peak_change_mm": entry.get("peak_change_mm"), "seconds": info["seconds"],
           "exit_code": info["exit_code"], "named": None, "coverage": []}
    dj = d / "diagnosis" / "diagnosis.json"
    if info["exit_code"] != 0 or not dj.exists():
        return row
    dia = json.loads(dj.read_text())
    # the physics named (a candidate that is another form of a physics names that physics)
    row["named"] = sorted(dia.get("discovered_physics", dia.get("discovered", [])))
    row["named_forms"] = sorted(dia.get("discovered", []))
    forms = forms_of(dia.get("discovered_forms", []))
    row["forms"] = {phys: f["term"] for phys, f in forms.items()}
    row["truth_forms"] = truth_forms(entry)
    row["verdict"] = dia.get("verdict")
    params = {p["name"]: p for p in dia.get("final", {}).get("parameters", [])}
    row["fitted"] = {k: p.get("value") for k, p in params.items()}
    row["coverage"] = coverage_rows(entry, row["named"], params, pseudo_true_of_named(record, forms), forms)
    row["field"] = field_row(dia.get("field"), entry)
    row["law"] = field_row(dia.get("law"), entry)
    for built in (row["field"], row["law"]):  # a modelled field or law names its physics family
        if built and built["accepted"]:
            row["named"] = sorted(set(row["named"]) | {built["family"]})
    return row


def truth_centre(entry):
    """The centre [m] of a localised hidden effect (the manifest's derived
    centre_m of the first effect that has one), or None."""
    for e in entry.get("effects", []):
        c = (e.get("derived") or {}).get("centre_m")
        if c is not None:
            return c
    return None


def field_row(field, entry):
    """The diagnosis' stiffness field or tissue law (docs/DISCOVERY.md):
    whether it was tried and accepted, chi2/dof before and after, and for a
    field and a localised hidden effect the distance [mm] from its centre to
    the field's centroid."""
    if not field or not field.get("tried"):
        return None
    row = {"accepted": bool(field.get("accepted")), "family": field.get("family", "tissue_field"),
           "failed": field.get("failed", [])}
    if "chi2_after" in field and field.get("dof_after"):
        dof = field["dof_after"]
        row["chi2_dof_before"] = (field["chi2_after"] + field.get("likelihood_ratio", 0.0)) / dof
        row["chi2_dof_after"] = field["chi2_after"] / dof
    centre, summary = truth_centre(entry), field.get("summary") or {}
    if centre is not None and summary.get("centroid_m") is not None:
        row["location_error_mm"] = 1e3 * math.dist(centre, summary["centroid_m"])
    return row


def field_summary(done, key="field"):
    """Over the rows whose diagnosis tried a field (key "field") or a law
    ("law"): how many it modelled, the localisation error of the modelled
    ones (median, largest) and their chi2/dof before and after (median)."""
    tried = [r[key] for r in done if r.get(key)]
    kept = [f for f in tried if f["accepted"]]
    loc = [f["location_error_mm"] for f in kept if "location_error_mm" in f]
    med = lambda v: statistics.median(v) if v else None
    return {"tried": len(tried), "modelled": len(kept),
            "location_error_mm": {"median": med(loc), "max": max(loc) if loc else None, "of": len(loc)},
            "chi2_dof_before": med([f["chi2_dof_before"] for f in kept if "chi2_dof_before" in f]),
            "chi2_dof_after": med([f["chi2_dof_after"] for f in kept if "chi2_dof_after" in f])}


def truth_forms(entry):
    """{physics: candidate form} of the hidden effects whose truth variant
    has a form of its own in the library (FORM_OF_VARIANT)."""
    out = {}
    for eff in entry.get("effects", []):
        form = FORM_OF_VARIANT.get(eff.get("pattern", {}).get("variant"))
        if form:
            out[eff["candidate"]] = form
    return out


@functools.lru_cache(maxsize=None)
def family_of_form():
    """{candidate: its physics} as the forms declare it (forms/model.py
    CANDIDATES: a candidate that is another form of a physics names it)."""
    import importlib.util
    path = REPO / "forms" / "model.py"
    spec = importlib.util.spec_from_file_location("breastsim_forms_model", path)
    model = importlib.util.module_from_spec(spec)
    sys.path.insert(0, str(path.parent))  # model.py imports its sibling term modules
    try:
        spec.loader.exec_module(model)  # needs UFL: the forms' own registry
    finally:
        sys.path.pop(0)
    return {name: c["family"] for name, c in model.CANDIDATES.items()}


def form_tally(rows):
    """Over the hidden physics named: how often each form carried it
    ({physics: {form: count}}), and, where the truth's form is known, how
    often the named form is that one."""
    tally, matched, known = {}, 0, 0
    for r in rows:
        for phys, form in (r.get("forms") or {}).items():
            if phys not in r["hidden"]:
                continue
            tally.setdefault(phys, {}).setdefault(form, 0)
            tally[phys][form] += 1
            truth = (r.get("truth_forms") or {}).get(phys)
            if truth:
                known += 1
                matched += form == truth
    return {"by_physics": tally, "truth_form_named": matched, "truth_form_known": known}


def covered_effects(entry, named):
    """The hidden effects of `entry` with an equivalent q that the diagnosis
    named, in manifest order: the ones a coverage row is made for."""
    return [e for e in entry.get("effects", []) if e.get("q_equivalent") and e["candidate"] in named]


def forms_of(discovered_forms):
    """{physics: {"term", "parameter"}} of diagnosis.json discovered_forms.
    A physics' form is its base term, with the regional variations that
    extend it joined by '+' (e.g. skin+skin_upper_pole): a form of its own,
    whose parameter is the base's, compared only with that form's
    pseudo-true value; "extension_parameters" lists the variations' own
    parameters."""
    forms = {}
    for f in sorted(discovered_forms, key=lambda f: bool(f.get("extends"))):
        if f["physics"] in forms:
            base = forms[f["physics"]]
            forms[f["physics"]] = {**base, "term": base["term"] + "+" + f["term"],
                                   "extension_parameters": base.get("extension_parameters", []) + [f["parameter"]]}
        else:
            forms[f["physics"]] = f
    return forms


def coverage_rows(entry, named, params, pseudo, forms=None):
    """Per hidden effect the diagnosis named: its reference q (pseudo-true
    where computed, `pseudo` {candidate or form: q*}, else the equivalent)
    against the fitted parameter's 95 % interval (`params` {parameter:
    {"value", "interval95"}}). An effect named in another form of its
    physics (`forms` {physics: {"term", "parameter"}}, diagnosis.json
    discovered_forms) has that form's parameter and pseudo-true value, and
    no equivalent. A form with regional variations keeps its variations'
    intervals under "extensions", and is covered only if every parameter's
    pseudo-true value ({parameter: q*}) is inside its interval."""
    rows = []
    for eff in covered_effects(entry, named):
        q = eff["q_equivalent"]
        form = (forms or {}).get(eff["candidate"], {"term": eff["candidate"], "parameter": q["parameter"]})
        other = form["term"] != eff["candidate"]
        ref, extensions = reference_of(form, pseudo.get(form["term"]), params)
        if other and ref is None:
            q = {**q, "value": None}          # no reference for the other form yet
        fitted = params.get(form["parameter"])
        base = interval_check(form["parameter"], ref if ref is not None else q["value"], fitted)
        rows.append({"candidate": eff["candidate"], "parameter": form["parameter"], "form": form["term"],
                     "truth": q["value"], "approximate": bool(q.get("approximate")),
                     "fitted": base["fitted"], "interval95": base["interval95"],
                     "inside": interval_check(form["parameter"], q["value"], fitted)["inside"],
                     "pseudo_true": ref, "reference": base["reference"],
                     "reference_kind": "pseudo-true" if ref is not None else "equivalent",
                     "inside_reference": None if base["inside"] is None
                     else base["inside"] and all(x["inside"] for x in extensions),
                     "extensions": extensions,
                     # named in another form of the physics without its pseudo-true value yet
                     "other_form": other and ref is None})
    return rows


def reference_of(form, ref, params):
    """(the pseudo-true value of the form's parameter or None, the checks of
    its variations' parameters): `ref` is q* or, for a form with regional
    variations, {parameter: q*}, which counts only if every variation's
    interval is known."""
    checks = [interval_check(x, ref.get(x) if isinstance(ref, dict) else None, params.get(x))
              for x in form.get("extension_parameters", [])]
    if not isinstance(ref, dict):
        return ref, checks
    if set(ref) != {form["parameter"], *form.get("extension_parameters", [])} or any(
            c["inside"] is None for c in checks):
        return None, checks
    return ref[form["parameter"]], checks


def interval_check(parameter, reference, fitted):
    """{parameter, reference, fitted, interval95, inside}: is `reference`
    inside the 95 % interval of `fitted` ({"value", "interval95"}; None:
    unknown)?"""
    lo, hi = (fitted or {}).get("interval95", [None, None])
    inside = None if lo is None or hi is None or reference is None else bool(lo <= reference <= hi)
    return {"parameter": parameter, "reference": reference, "fitted": (fitted or {}).get("value"),
            "interval95": [lo, hi], "inside": inside}


def ratio(a, b):
    return None if b == 0 else a / b


def summarize(rows):
    done = [r for r in rows if r["named"] is not None]
    failed = [r["name"] for r in rows if r["named"] is None]
    labels = sorted({r["hidden_label"] for r in done}, key=lambda s: (s != "none", "+" in s, s))
    columns = CANDIDATES + ["none"]
    matrix = {lab: {c: 0 for c in columns} for lab in labels}
    for r in done:
        for c in (r["named"] or ["none"]):
            matrix[r["hidden_label"]].setdefault(c, 0)
            matrix[r["hidden_label"]][c] += 1
    exact = lambda r: r["named"] == r["hidden"]
    singles = [r for r in done if len(r["hidden"]) == 1]
    pairs = [r for r in done if len(r["hidden"]) == 2]
    controls = [r for r in done if not r["hidden"]]
    named_terms = sum(len(r["named"]) for r in done)
    false_terms = sum(len(set(r["named"]) - set(r["hidden"])) for r in done)
    cov = [c for r in done for c in r["coverage"] if c["inside"] is not None]
    cov_exact = [c for c in cov if not c["approximate"]]
    cov_ref = [c for c in cov if c["inside_reference"] is not None]
    cov_pseudo = [c for c in cov_ref if c["reference_kind"] == "pseudo-true"]
    times = [r["seconds"] for r in done]
    by_class = {}
    for cls in sorted({r["class"] for r in singles}):
        sub = [r for r in singles if r["class"] == cls]
        by_class[cls] = {"exact": sum(map(exact, sub)), "of": len(sub)}
    s = {
        "recordings_scored": len(done), "failed_or_missing": failed,
        "confusion": matrix,
        "single_effect": {"exact": sum(map(exact, singles)), "of": len(singles),
                          "rate": ratio(sum(map(exact, singles)), len(singles)),
                          "named_hidden_with_extra": sum(1 for r in singles if set(r["hidden"]) < set(r["named"])),
                          "missed": sum(1 for r in singles if not set(r["hidden"]) & set(r["named"])),
                          "by_class": by_class},
        "pairs": {"exact": sum(map(exact, pairs)), "of": len(pairs)},
        "controls": {"false_discoveries": sum(1 for r in controls if r["named"]), "of": len(controls),
                     "names": [r["name"] for r in controls if r["named"]]},
        "false_discovery_rate": {"false_terms": false_terms, "named_terms": named_terms,
                                 "rate": ratio(false_terms, named_terms)},
        "coverage": {"inside": sum(c["inside"] for c in cov), "of": len(cov),
                     "rate": ratio(sum(c["inside"] for c in cov), len(cov)),
                     "exact_equivalents_inside": sum(c["inside"] for c in cov_exact),
                     "exact_equivalents_of": len(cov_exact),
                     "named_in_another_form": sum(1 for r in done for c in r["coverage"] if c.get("other_form"))},
        "coverage_reference": {"inside": sum(c["inside_reference"] for c in cov_ref), "of": len(cov_ref),
                               "rate": ratio(sum(c["inside_reference"] for c in cov_ref), len(cov_ref)),
                               "pseudo_true_inside": sum(c["inside_reference"] for c in cov_pseudo),
                               "pseudo_true_of": len(cov_pseudo)},
        "forms": form_tally(done),
        "field": field_summary(done),
        "law": field_summary(done, "law"),
        "seconds": {"median": statistics.median(times) if times else None,
                    "min": min(times) if times else None, "max": max(times) if times else None},
    }
    s["targets"] = {
        "single_exact>=0.95": s["single_effect"]["rate"] is not None and s["single_effect"]["rate"] >= TARGET_EXACT,
        "controls>=12_and_no_false_discovery": len(controls) >= MIN_CONTROLS and s["controls"]["false_discoveries"] == 0,
        "coverage>=0.90": (s["coverage_reference"]["rate"] is not None
                           and s["coverage_reference"]["rate"] >= TARGET_COVERAGE),
        "median<=120s": s["seconds"]["median"] is not None and s["seconds"]["median"] <= TARGET_MEDIAN_S,
    }
    return s


def fmt(x, spec=".3g"):
    return "-" if x is None else format(x, spec)


def field_lines(fs, what="stiffness field"):
    """The summary's line of the stiffness field or the tissue law (none if
    no diagnosis tried one)."""
    if not fs or not fs["tried"]:
        return []
    loc = fs["location_error_mm"]
    where = (f"; centroid to the truth's centre: median {fmt(loc['median'], '.1f')} mm, largest "
             f"{fmt(loc['max'], '.1f')} mm (of {loc['of']})" if loc["of"] else "")
    return [f"- {what} (docs/DISCOVERY.md): modelled in {fs['modelled']} of {fs['tried']} diagnoses "
            f"that tried one; chi2/dof median {fmt(fs['chi2_dof_before'], '.3f')} -> "
            f"{fmt(fs['chi2_dof_after'], '.3f')}{where}"]


def markdown(s, rows, command):
    out = [f"Command: `{command}`", "",
           "Each diagnosis: `breastsim -q diagnose REC --case CASE "
           + " ".join(f"--set {x}" for x in BASELINE_SETS) + " " + " ".join(DISCRETISATION)
           + f" --fit {FIT} --out ... [EXTRA]`", ""]
    seen = {c for counts in s["confusion"].values() for c in counts}
    cols = CANDIDATES + sorted(seen - set(CANDIDATES) - {"none"}) + ["none"]  # + families outside the library
    out += ["| hidden \\ named | " + " | ".join(cols) + " |", "|---" * (len(cols) + 1) + "|"]
    for lab, counts in s["confusion"].items():
        out.append(f"| {lab} | " + " | ".join(str(counts.get(c, 0)) for c in cols) + " |")
    se, c, f, cv, t = s["single_effect"], s["controls"], s["false_discovery_rate"], s["coverage"], s["seconds"]
    cr, form_counts = s["coverage_reference"], s.get("forms", {})
    out += ["",
            f"- single-effect recordings named exactly: {se['exact']} of {se['of']} "
            f"({fmt(se['rate'], '.0%')}); by class: "
            + ", ".join(f"{k} {v['exact']}/{v['of']}" for k, v in se["by_class"].items())
            + f"; hidden named plus extra terms: {se['named_hidden_with_extra']}; hidden missed: {se['missed']}",
            f"- two-effect recordings named exactly: {s['pairs']['exact']} of {s['pairs']['of']}",
            f"- controls with a false discovery: {c['false_discoveries']} of {c['of']}"
            + (f" ({', '.join(c['names'])})" if c["names"] else ""),
            f"- false-discovery rate (named terms not hidden / named terms): {f['false_terms']} / "
            f"{f['named_terms']} = {fmt(f['rate'], '.2f')}",
            f"- hidden q inside the reported 95 % interval: {cv['inside']} of {cv['of']} correct discoveries "
            f"({fmt(cv['rate'], '.0%')}; with an exact equivalent: {cv['exact_equivalents_inside']} of "
            f"{cv['exact_equivalents_of']}; named in another form of the physics, without that "
            f"form's pseudo-true value: {cv.get('named_in_another_form', 0)})",
            f"- reference q (the pseudo-true value where computed, else the equivalent) inside the 95 % "
            f"interval: {cr['inside']} of {cr['of']} ({fmt(cr['rate'], '.0%')}; pseudo-true values: "
            f"{cr['pseudo_true_inside']} of {cr['pseudo_true_of']})",
            "- forms of the hidden physics named: " + (
                "; ".join(f"{ph} " + ", ".join(f"as {fm} {n}" for fm, n in sorted(t.items()))
                          for ph, t in sorted(form_counts.get("by_physics", {}).items())) or "none")
            + (f" (the truth's own form where it has one: {form_counts['truth_form_named']} of "
               f"{form_counts['truth_form_known']})" if form_counts.get("truth_form_known") else ""),
            f"- time per diagnosis: median {fmt(t['median'], '.1f')} s (min {fmt(t['min'], '.1f')}, "
            f"max {fmt(t['max'], '.1f')})",
            *field_lines(s.get("field")),
            *field_lines(s.get("law"), "tissue law"),
            f"- not scored (failed or not run): {', '.join(s['failed_or_missing']) or 'none'}",
            "", "| recording | class | hidden | peak [mm] | named | q equivalent | q pseudo-true | "
            "fitted [95 % interval] | s |",
            "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r is None:
            continue
        cov = "; ".join(fmt(x['truth']) for x in r["coverage"]) or "-"
        pst = "; ".join(fmt(x.get("pseudo_true")) + "".join(f" ({e['parameter']} {fmt(e['reference'])})"
                                                            for e in x.get("extensions", []) if e["reference"])
                        for x in r["coverage"]) or "-"
        fit = "; ".join(f"{fmt(x['fitted'])} [{fmt(x['interval95'][0])}, {fmt(x['interval95'][1])}]"
                        + "".join(f" ({e['parameter']} {fmt(e['fitted'])} [{fmt(e['interval95'][0])}, "
                                  f"{fmt(e['interval95'][1])}])" for e in x.get("extensions", []))
                        for x in r["coverage"]) or "-"
        named = "failed" if r["named"] is None else ("+".join(r["named"]) or "none")
        if r["named"] and r.get("named_forms") and r["named_forms"] != r["named"]:
            named += " (as " + "+".join(r["named_forms"]) + ")"
        out.append(f"| {r['name']} | {r['class']} | {r['hidden_label']} | {fmt(r['peak_change_mm'])} | "
                   f"{named} | {cov} | {pst} | {fit} | {r['seconds']:.1f} |")
    return "\n".join(out) + "\n"


# -- command line ------------------------------------------------------------------
def select(manifest, only, classes, limit):
    entries = list(manifest["recordings"].values())
    if only:
        unknown = set(only) - {e["name"] for e in entries}
        if unknown:
            sys.exit(f"run_diagnose.py: unknown recording(s) {sorted(unknown)}")
        entries = [e for e in entries if e["name"] in only]
    if classes:
        bad = set(classes) - {"control", "weak", "strong", "pair"}
        if bad:
            sys.exit(f"run_diagnose.py: unknown class(es) {sorted(bad)} (control, weak, strong, pair)")
        entries = [e for e in entries if e["strength_class"] in classes]
    return entries[:limit] if limit else entries


def parse_args(argv):
    ap = argparse.ArgumentParser(description="diagnose the independent-truth recordings")
    ap.add_argument("build", nargs="?", help="build folder holding breastsim")
    ap.add_argument("--manifest", default=str(HERE / "manifest.json"))
    ap.add_argument("--out", default=str(HERE / "results"))
    ap.add_argument("--case", default=str(REPO / "cases" / "default.toml"))
    ap.add_argument("--only", action="append", default=[], help="recording names (comma-separated)")
    ap.add_argument("--classes", default="", help="subset of control,weak,strong,pair")
    ap.add_argument("--limit", type=int, default=0, help="at most N recordings")
    ap.add_argument("--extra", default="", help="further diagnose arguments (quoted)")
    ap.add_argument("--nice", type=int, default=19, help="niceness of the diagnoses (-1: none)")
    ap.add_argument("--rerun", action="store_true", help="diagnose again where a result exists")
    ap.add_argument("--jobs", type=int, default=1,
                    help="diagnoses run at once (each its own process; time per diagnosis then "
                         "includes the sharing of the cores)")
    ap.add_argument("--mpi", type=int, default=0,
                    help="run each diagnosis as mpirun -n MPI (0: one process)")
    ap.add_argument("--ranks-per-case", type=int, default=1,
                    help="with --mpi: MPI ranks per forward solve (diagnose --ranks-per-case)")
    ap.add_argument("--summarize-only", action="store_true", help="only score existing results")
    ap.add_argument("--expect-exact", action="store_true",
                    help="exit 1 unless every selected recording is diagnosed and named exactly "
                         "(the hidden terms, nothing else)")
    a = ap.parse_args(argv)
    a.only = [n for item in a.only for n in item.split(",") if n]
    a.classes = [c for c in a.classes.split(",") if c]
    if a.limit < 0:
        ap.error("--limit must be >= 0")
    if a.jobs < 1:
        ap.error("--jobs must be >= 1")
    if a.mpi < 0 or (a.mpi and (a.ranks_per_case < 1 or a.mpi % a.ranks_per_case)):
        ap.error(f"--mpi {a.mpi} --ranks-per-case {a.ranks_per_case}: need --mpi >= 0 and a "
                 "--ranks-per-case >= 1 that divides it")
    if not a.summarize_only and not a.build:
        ap.error("BUILD_DIR is required (or --summarize-only)")
    return a


def main(argv=None):
    a = parse_args(sys.argv[1:] if argv is None else argv)
    manifest_path = Path(a.manifest)
    if not manifest_path.exists():
        sys.exit(f"run_diagnose.py: no manifest {manifest_path} (generate.py writes it)")
    manifest = json.loads(manifest_path.read_text())
    entries = select(manifest, a.only, a.classes, a.limit)
    records = pseudo_true_recordings(manifest_path.parent)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    if not a.summarize_only:
        binary = Path(a.build) / "breastsim"
        if not binary.exists():
            sys.exit(f"run_diagnose.py: {binary} does not exist (build breastsim first)")
        nice = None if a.nice < 0 else a.nice
        mpi = (a.mpi, a.ranks_per_case) if a.mpi else None

        def run_and_print(e):
            state = run_one(binary, manifest_path.parent, e, out, a.case, shlex.split(a.extra), nice,
                            a.rerun, mpi)
            row = read_result(out, e, records.get(e["name"]))
            named = "-" if row is None or row["named"] is None else ("+".join(row["named"]) or "none")
            print(f"{e['name']:<40} {state:<8} hidden {e['hidden_label']:<35} named {named:<30} "
                  f"{'' if row is None else format(row['seconds'], '.1f') + ' s'}", flush=True)

        # --jobs N: N diagnoses at once (independent processes), in manifest order.
        with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
            list(pool.map(run_and_print, entries))
    rows = [read_result(out, e, records.get(e["name"])) for e in entries]
    scored = [r for r in rows if r is not None]
    summary = summarize(scored)
    command = "python3 bench/truth/run_diagnose.py " + " ".join(shlex.quote(x) for x in (argv or sys.argv[1:]))
    summary["command"] = command
    summary["rows"] = scored
    (out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    text = markdown(summary, scored, command)
    (out / "summary.md").write_text(text)
    print(text)
    if a.expect_exact:
        wrong = [e["name"] for e, r in zip(entries, rows)
                 if r is None or r["named"] is None or set(r["named"]) != set(e["hidden"])]
        if wrong:
            print(f"run_diagnose.py: not named exactly: {', '.join(wrong)}")
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
