#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Pseudo-true values of the candidates for the independent-truth recordings.

The hidden effects have other forms than breastsim's candidates, so "the
hidden value" of a candidate parameter needs a definition. The manifest's
q_equivalent is a linearised or averaged stand-in. The pseudo-true value is
the one a fit converges to with noise-free data and no discretisation
difference, of the model family the diagnosis fits: every hidden effect of
a recording with a candidate form in the truth code
(forms_truth/candidate_forms.py: base_springs, gland_core,
suspensory_ligament, skin) is replaced by the candidate's form, all of them
together (the diagnosis fits the candidates of a pair jointly; an effect
without a form would stay as in the truth), and their values are fitted
together with the tissue's mu and lambda (the diagnosis fits them too,
--fit mu,lambda; a form difference moves them):

    (q*, mu*, lambda*) = argmin sum_postures int_skin ((u - u_truth) . n)^2 dA,

q the vector of the replaced effects' parameters, n the unit normal of the
truth's deformed skin, both solved on the truth's own P2 mesh. Gauss-Newton
in ln (q, mu, lambda) with a forward-difference Jacobian (one column per
parameter), from the values with mu, lambda fixed where known, else the
manifest's equivalents, and the truth's mu, lambda. Also reported: mu*,
lambda* ("material"), the share of the effects the candidates' forms leave
unexplained, ||r*|| / ||r(replaced effects removed)|| (0: the forms agree;
near 1: the candidates cannot reproduce them), the same for every candidate
of a joint fit ("joint" lists them), and the values of the earlier
definition with mu, lambda fixed at the truth's ("material_fixed").

Definition version 3 (this one); version 2 held mu, lambda at the truth's,
version 1 also replaced each effect of a pair alone. Entries of another
version are recomputed.

    nice -n 19 python3 bench/truth/pseudo_true.py              # main set, missing or outdated entries
    nice -n 19 python3 bench/truth/pseudo_true.py --set validation
    python3 bench/truth/pseudo_true.py --only base_springs_weak_1 --redo
    python3 bench/truth/pseudo_true.py --only A,B --out /tmp/part.json   # a second process: its own file

Another form of a candidate's physics (forms_truth/candidate_forms.py
ALTERNATIVE_FORMS, e.g. the ligaments as cables) gets its own pseudo-true value
with `--form suspensory_ligament=suspensory_cables`: the same fit with that
form in place of the physics' candidate, stored under the recording's
"other_forms" (run_diagnose.py compares a discovery named in that form with
it). So does a candidate with a regional variation that extends it
(EXTENSIONS, e.g. `--form skin=skin+skin_upper_pole`): both terms in place
of the physics' effects, one q each, fitted jointly with mu and lambda (the
variation starts at EXTENSION_START times the candidate's start).

    nice -n 19 python3 bench/truth/pseudo_true.py --form suspensory_ligament=suspensory_cables --only A,B
    nice -n 19 python3 bench/truth/pseudo_true.py --form skin=skin+skin_upper_pole --only skin_strong_3

Writes pseudo_true.json beside the manifest, one entry per recording as
soon as it is done (resumable). A recording whose fit meets a posture the
truth's solver cannot solve is reported, left without an entry, and the
others go on (exit code 1 at the end).
"""
import argparse
import math
import sys
import time
from pathlib import Path

from generate import HERE, R, H, ensure_dolfinx

ensure_dolfinx()

import numpy as np  # noqa: E402

import benchmark_set  # noqa: E402

from forms_truth.candidate_forms import ALTERNATIVE_FORMS, CANDIDATE_FORMS, physics_of_form  # noqa: E402
from geometry import build_half_cap  # noqa: E402
from problem import Problems  # noqa: E402
from recording_io import read_manifest, write_json_atomic  # noqa: E402
from solver import SolveError  # noqa: E402
from surface import Skin  # noqa: E402

DEFINITION = ("(q*, mu*, lambda*) = argmin sum_postures int_skin ((u - u_truth) . n)^2 dA: every hidden "
              "effect with a candidate form replaced by the candidate's form (forms_truth/candidate_forms.py), "
              "their q fitted jointly with the tissue's mu and lambda; other hidden effects as in the truth, "
              "both solved on the truth's P2 mesh; n the truth's deformed skin normal")
DEFINITION_VERSION = 3
MATERIAL = ("mu", "lambda")   # fitted with the candidates, as the diagnosis fits them (--fit mu,lambda)
STEP = 0.05          # forward-difference step in ln q
MAX_ITERATIONS = 8
TOL_LOG = 0.005      # stop when |delta ln q| is below this
MAX_LOG_STEP = 1.5   # at most a factor e^1.5 per Gauss-Newton step
EXTENSION_START = 0.5  # a regional variation's q starts at this times its base's start


class Fitter:
    def __init__(self, mesh_size, chest_wall_k=None):
        mesh, facets = build_half_cap(R, H, mesh_size, order=2)
        self.problems = Problems(mesh, facets, R, H, chest_wall_k)
        self.skin = Skin(self.problems.ctx[2])
        self.sqrt_w = None

    def solve(self, entry, effects, strengths, starts=None, material=None):
        """`material` overrides entry["material"] (mu, lambda)."""
        prob = self.problems.get(2, effects)
        prob.configure({**entry["material"], **(material or {})}, effects, strengths)
        return prob.solve_postures(entry["postures"], entry["material"]["rho"], starts)

    def residual(self, u_truth, u):
        """sqrt(w) ((u - u_truth) . n) over postures and skin triangle nodes,
        w = deformed triangle area / 6 (a nodal rule for int dA)."""
        parts = []
        for ut, ui in zip(u_truth, u):
            w = np.sqrt(self.skin.areas(ut) / 6.0)[:, None]
            parts.append((w * self.skin.normal_difference(ut, ui)).ravel())
        return np.concatenate(parts)

    def truth(self, entry):
        """The recording's truth solves, one per posture."""
        hidden = [(e["model"], e["pattern"]) for e in entry["effects"]]
        return self.solve(entry, hidden, {e["model"]: e["strength"]["value"] for e in entry["effects"]})

    def fit(self, entry, indices=None, u_truth=None, start=None, form=None):
        """{candidate: q* and its figures} of the candidates replacing the
        hidden effects `indices` jointly (default: every effect with a
        candidate form), mu and lambda fitted with them; `u_truth`: the truth
        solves, computed here if not given; `start`: starting values by
        candidate or "mu", "lambda" (default: the equivalents, the truth's);
        `form`: (physics, FORM) replaces that physics' effects by the
        alternative form FORM instead (ALTERNATIVE_FORMS: another form, or
        the candidate with a regional variation, one q per term), its
        values keyed by each term's name."""
        hidden = [(e["model"], e["pattern"]) for e in entry["effects"]]
        strengths = {e["model"]: e["strength"]["value"] for e in entry["effects"]}
        indices = replaceable(entry) if indices is None else list(indices)
        u_truth = self.truth(entry) if u_truth is None else u_truth
        groups = [(entry["effects"][k], ALTERNATIVE_FORMS[form[1]] if form and entry["effects"][k]["candidate"]
                   == form[0] else [CANDIDATE_FORMS[entry["effects"][k]["candidate"]]]) for k in indices]
        targets = [t for t, g in groups for _ in g]                # the hidden effect each form replaces
        forms = [f for _, g in groups for f in g]
        others = [h for k, h in enumerate(hidden) if k not in indices]
        u_none = self.solve(entry, others, strengths, u_truth)     # the truth without the replaced effects
        effects = others + [(f.NAME, {}) for f in forms]
        n = len(forms)

        def evaluate(y, start):
            # y = (ln q of each form, ln mu, ln lambda)
            u = self.solve(entry, effects, {**strengths, **{f.NAME: math.exp(v) for f, v in zip(forms, y[:n])}},
                           start, {k: math.exp(v) for k, v in zip(MATERIAL, y[n:])})
            return u, self.residual(u_truth, u)

        start = start or {}
        y0 = np.log([initial_value(f, t, start) for f, t in zip(forms, targets)]
                    + [start.get(k, entry["material"][k]) for k in MATERIAL])
        y, r, history = gauss_newton(evaluate, y0, u_truth)
        effect_norm = float(np.linalg.norm(self.residual(u_truth, u_none)))
        return results(targets, forms, y[:n], history, {
            "unexplained_share": float(np.linalg.norm(r)) / effect_norm if effect_norm > 0 else None,
            "effect_rms_mm": 1e3 * effect_norm / math.sqrt(self._area_sum(u_truth)),
            "material": {k: math.exp(v) for k, v in zip(MATERIAL, y[n:])}})

    def _area_sum(self, u_truth):
        return sum(float(self.skin.areas(ut).sum()) for ut in u_truth)


def gauss_newton(evaluate, y, start):
    """min_y ||r(y)|| from y (evaluate(y, start) -> (solves, r)): Gauss-Newton
    J dy = -r in least squares, J by forward differences (column i:
    (r(y + STEP e_i) - r(y)) / STEP), dy scaled to |dy_i| <= MAX_LOG_STEP and
    halved while ||r|| does not decrease; history [q_1, ..., ||r||] per step."""
    u, r = evaluate(y, start)
    history = []
    for _ in range(MAX_ITERATIONS):
        columns, u_d = [], u
        for i in range(len(y)):
            u_d, r_d = evaluate(y + STEP * np.eye(len(y))[i], u)
            columns.append((r_d - r) / STEP)
        dy = -np.linalg.lstsq(np.stack(columns, axis=1), r, rcond=None)[0]
        dy *= min(1.0, MAX_LOG_STEP / max(np.abs(dy).max(), 1e-300))
        history.append([round(math.exp(v), 12) for v in y] + [float(np.linalg.norm(r))])
        u_new, r_new = evaluate(y + dy, u_d)
        while np.linalg.norm(r_new) > np.linalg.norm(r) and np.abs(dy).max() > TOL_LOG:
            dy *= 0.5                                   # backtrack
            u_new, r_new = evaluate(y + dy, u)
        if np.linalg.norm(r_new) <= np.linalg.norm(r):
            y, u, r = y + dy, u_new, r_new
        if np.abs(dy).max() < TOL_LOG:
            break
    return y, r, history


def initial_value(form, target, start):
    """The start of a form's q: `start`'s value of the replaced effect's
    candidate, else its equivalent; a regional variation (EXTENDS) starts
    at EXTENSION_START times that."""
    q = start.get(target["candidate"], target["q_equivalent"]["value"])
    return q * EXTENSION_START if getattr(form, "EXTENDS", None) else q


def results(targets, forms, y, history, common):
    """Per candidate form: its q*, its equivalent (none for another form of
    the physics or a regional variation), the figures `common` to the fit
    and its column of the history ([q, ||r||] per step); "joint" when
    several forms are fitted together."""
    if len(forms) > 1:
        common = {**common, "joint": [f.CANDIDATE for f in forms]}
    out = {}
    for i, (t, f) in enumerate(zip(targets, forms)):
        same = f.CANDIDATE == t["candidate"]
        out[f.CANDIDATE] = {"parameter": t["q_equivalent"]["parameter"] if same else f.PARAMETER,
                            "value": math.exp(y[i]), "equivalent": t["q_equivalent"]["value"] if same else None,
                            **common, "history": [[h[i], h[-1]] for h in history]}
    return out


def replaceable(entry):
    """Indices of the hidden effects that have a candidate form."""
    return [k for k, e in enumerate(entry["effects"]) if e["candidate"] in CANDIDATE_FORMS]


def is_current(stored):
    """A stored entry computed under DEFINITION."""
    return stored.get("definition_version", 1) == DEFINITION_VERSION


def material_fixed_values(stored):
    """{candidate: q*} of an entry of version 1 or 2 (mu, lambda the truth's), {} if none."""
    if not stored or is_current(stored):
        return (stored or {}).get("material_fixed", {})
    return {c: v["value"] for c, v in stored["candidates"].items()}


def fmt(x):
    return "-" if x is None else f"{x:.4g}"


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--set", dest="which", choices=benchmark_set.SETS, default="main")
    ap.add_argument("--only", default="", help="recording names (comma-separated; computed in this order)")
    ap.add_argument("--redo", action="store_true", help="recompute existing entries")
    ap.add_argument("--folder", default=None, help="folder of manifest.json (default: by --set)")
    ap.add_argument("--out", default=None, help="output file (default: pseudo_true.json beside the manifest; "
                                                "one process per file)")
    allowed = ", ".join(f"{physics_of_form(n)}={n}" for n in ALTERNATIVE_FORMS)
    ap.add_argument("--form", default=None, metavar="PHYSICS=FORM",
                    help=f"replace the effects of PHYSICS by its alternative form FORM ({allowed}; a '+' "
                    "joins a regional variation to the candidate, fitted jointly); stored under the "
                    "recording's other_forms.FORM")
    a = ap.parse_args()
    if a.form is not None:
        physics, _, form = a.form.partition("=")
        if form not in ALTERNATIVE_FORMS or physics_of_form(form) != physics:
            ap.error(f"--form {a.form}: allowed: {allowed}")
        a.form = (physics, form)
    return a


def pending(a, name, entry, stored, only):
    """True if recording `name` is to be computed: selected, with an effect
    to replace, and not stored under the current definition (--redo: always)."""
    if only and name not in only:
        return False
    if a.form:
        return (any(e["candidate"] == a.form[0] for e in entry["effects"])
                and (a.redo or a.form[1] not in (stored or {}).get("other_forms", {})))
    return bool(replaceable(entry)) and (a.redo or not stored or not is_current(stored))


def compute(fitter, a, name, entry, stored, previous):
    """The recording's new stored entry: the candidates' values (keeping
    other forms stored before), or with --form that form's values added."""
    t0 = time.perf_counter()
    if a.form:
        start = {c: v["value"] for c, v in (stored or {}).get("candidates", {}).items()}
        res = fitter.fit(entry, start=start, form=a.form)
        forms = {**(stored or {}).get("other_forms", {}), a.form[1]: res}
        return {**(stored or {}), "other_forms": forms}, res, time.perf_counter() - t0
    fixed = material_fixed_values(stored or previous.get(name))
    res = fitter.fit(entry, start=fixed)
    new = {"seconds": round(time.perf_counter() - t0, 1), "definition_version": DEFINITION_VERSION,
           "candidates": res, "material_fixed": fixed}
    if stored and "other_forms" in stored:
        new["other_forms"] = stored["other_forms"]
    return new, res, time.perf_counter() - t0


def compute_each(todo, compute_one, store):
    """store(name, compute_one(name, entry)) for each (name, entry) of todo;
    a recording whose fit meets a posture the truth cannot solve
    (SolveError) is reported and skipped, and the others go on. Returns
    the names skipped."""
    failed = []
    for name, entry in todo:
        try:
            result = compute_one(name, entry)
        except SolveError as e:
            print(f"{name}: not computed: {e}", file=sys.stderr, flush=True)
            failed.append(name)
            continue
        store(name, result)
    return failed


def main():
    a = parse_args()
    folder = Path(a.folder) if a.folder else (HERE if a.which == "main" else HERE / a.which)
    manifest = read_manifest(folder / "manifest.json")
    if manifest is None:
        sys.exit(f"pseudo_true.py: no manifest in {folder}")
    out_path = Path(a.out) if a.out else folder / "pseudo_true.json"
    previous = (read_manifest(folder / "pseudo_true.json") or {}).get("recordings", {})
    out = read_manifest(out_path) or {"format": 1, "generator": "bench/truth/pseudo_true.py",
                                      "definition": DEFINITION, "recordings": {}}
    only = [n for n in a.only.split(",") if n]
    out["definition"] = DEFINITION
    todo = [(n, e) for n, e in sorted(manifest["recordings"].items())
            if pending(a, n, e, out["recordings"].get(n), only)]
    if only:
        todo.sort(key=lambda item: only.index(item[0]))   # in the order given
    print(f"{len(todo)} recording(s)", flush=True)
    walls = {e["truth_mesh"].get("chest_wall_k_Pa_per_m") for _, e in todo}
    if len(walls) > 1:
        sys.exit(f"pseudo_true.py: the recordings' chest walls differ ({walls}); run them apart with --only")
    fitter = Fitter(0.006, walls.pop()) if todo else None
    for name, entry in todo:
        if entry["truth_mesh"]["size_m"] != 0.006 or entry["truth_mesh"].get("rim_size_m"):
            sys.exit(f"pseudo_true.py: {name}: truth mesh {entry['truth_mesh']} is not the uniform 6 mm mesh")

    def store(name, result):
        out["recordings"][name], res, seconds = result
        out["recordings"] = dict(sorted(out["recordings"].items()))
        write_json_atomic(out_path, out)
        print(name, {c: (f"{v['value']:.4g} (equivalent {fmt(v['equivalent'])}, "
                         f"unexplained {v['unexplained_share']:.2f})") for c, v in res.items()},
              f"{seconds:.1f} s", flush=True)
    failed = compute_each(todo, lambda n, e: compute(fitter, a, n, e, out["recordings"].get(n), previous), store)
    if failed:
        print(f"pseudo_true.py: not computed (a posture solve failed): {', '.join(failed)}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
