#!/usr/bin/env python3
"""Pseudo-true values of the candidates for the independent-truth recordings.

The hidden effects have other forms than breastsim's candidates, so "the
hidden value" of a candidate parameter needs a definition. The manifest's
q_equivalent is a linearised or averaged stand-in. The pseudo-true value is
the one a fit converges to with noise-free data and no discretisation
difference: for each hidden effect e with a candidate form in the truth code
(forms_truth/candidate_forms.py: base_springs, gland_core,
suspensory_ligament), e is replaced by the candidate's form (the other hidden
effects stay as they are, mu and lambda are the truth's) and its value is

    q* = argmin_q sum_postures int_skin ((u_q - u_truth) . n)^2 dA,

n the unit normal of the truth's deformed skin, both solved on the truth's
own P2 mesh. Gauss-Newton in ln q with a forward-difference derivative,
from the manifest's equivalent. Also reported: the share of the effect the
candidate form leaves unexplained, ||r(q*)|| / ||r(no effect)|| (0: the
forms agree; near 1: the candidate cannot reproduce the effect).

    nice -n 19 python3 bench/truth/pseudo_true.py              # main set, missing entries
    nice -n 19 python3 bench/truth/pseudo_true.py --set validation
    python3 bench/truth/pseudo_true.py --only base_springs_weak_1 --redo
    python3 bench/truth/pseudo_true.py --only A,B --out /tmp/part.json   # a second process: its own file

Writes pseudo_true.json beside the manifest, one entry per recording as
soon as it is done (resumable).
"""
import argparse
import math
import sys
import time
from pathlib import Path

from generate import HERE, R, H, ensure_dolfinx

ensure_dolfinx()

import numpy as np  # noqa: E402

from forms_truth.candidate_forms import CANDIDATE_FORMS  # noqa: E402
from geometry import build_half_cap  # noqa: E402
from problem import Problems  # noqa: E402
from recording_io import read_manifest, write_json_atomic  # noqa: E402
from surface import Skin  # noqa: E402

DEFINITION = ("q* = argmin_q sum_postures int_skin ((u_q - u_truth) . n)^2 dA: the hidden effect replaced "
              "by the candidate's form (forms_truth/candidate_forms.py), the other hidden effects and mu, "
              "lambda as in the truth, both solved on the truth's P2 mesh; n the truth's deformed skin normal")
STEP = 0.05          # forward-difference step in ln q
MAX_ITERATIONS = 8
TOL_LOG = 0.005      # stop when |delta ln q| is below this
MAX_LOG_STEP = 1.5   # at most a factor e^1.5 per Gauss-Newton step


class Fitter:
    def __init__(self, mesh_size):
        mesh, facets = build_half_cap(R, H, mesh_size, order=2)
        self.problems = Problems(mesh, facets, R, H)
        self.skin = Skin(self.problems.ctx[2])
        self.sqrt_w = None

    def solve(self, entry, effects, strengths, starts=None):
        prob = self.problems.get(2, effects)
        prob.configure(entry["material"], effects, strengths)
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

    def fit(self, entry, effect_index, u_truth=None):
        """q* of the candidate replacing hidden effect `effect_index`
        (`u_truth`: the truth solves, computed here if not given)."""
        hidden = [(e["model"], e["pattern"]) for e in entry["effects"]]
        strengths = {e["model"]: e["strength"]["value"] for e in entry["effects"]}
        u_truth = self.truth(entry) if u_truth is None else u_truth
        target = entry["effects"][effect_index]
        form = CANDIDATE_FORMS[target["candidate"]]
        others = [h for k, h in enumerate(hidden) if k != effect_index]
        u_none = self.solve(entry, others, strengths, u_truth)     # the truth without effect k
        effects = others + [(form.NAME, {})]

        def evaluate(y, start):
            u = self.solve(entry, effects, {**strengths, form.NAME: math.exp(y)}, start)
            return u, self.residual(u_truth, u)

        y = math.log(target["q_equivalent"]["value"])
        u, r = evaluate(y, u_truth)
        history = []
        for _ in range(MAX_ITERATIONS):
            u_d, r_d = evaluate(y + STEP, u)
            j = (r_d - r) / STEP
            dy = -float(j @ r) / float(j @ j)
            dy = max(-MAX_LOG_STEP, min(MAX_LOG_STEP, dy))
            history.append([round(math.exp(y), 12), float(np.linalg.norm(r))])
            u_new, r_new = evaluate(y + dy, u_d)
            while np.linalg.norm(r_new) > np.linalg.norm(r) and abs(dy) > TOL_LOG:
                dy *= 0.5                                   # backtrack
                u_new, r_new = evaluate(y + dy, u)
            if np.linalg.norm(r_new) <= np.linalg.norm(r):
                y, u, r = y + dy, u_new, r_new
            if abs(dy) < TOL_LOG:
                break
        effect_norm = float(np.linalg.norm(self.residual(u_truth, u_none)))
        return {"parameter": target["q_equivalent"]["parameter"], "value": math.exp(y),
                "equivalent": target["q_equivalent"]["value"],
                "unexplained_share": float(np.linalg.norm(r)) / effect_norm if effect_norm > 0 else None,
                "effect_rms_mm": 1e3 * effect_norm / math.sqrt(self._area_sum(u_truth)),
                "history": history}

    def _area_sum(self, u_truth):
        return sum(float(self.skin.areas(ut).sum()) for ut in u_truth)


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--set", dest="which", choices=["main", "validation"], default="main")
    ap.add_argument("--only", default="", help="recording names (comma-separated)")
    ap.add_argument("--redo", action="store_true", help="recompute existing entries")
    ap.add_argument("--out", default=None, help="output file (default: pseudo_true.json beside the manifest; "
                                                "one process per file)")
    return ap.parse_args()


def main():
    a = parse_args()
    folder = HERE if a.which == "main" else HERE / "validation"
    manifest = read_manifest(folder / "manifest.json")
    if manifest is None:
        sys.exit(f"pseudo_true.py: no manifest in {folder}")
    out_path = Path(a.out) if a.out else folder / "pseudo_true.json"
    out = read_manifest(out_path) or {"format": 1, "generator": "bench/truth/pseudo_true.py",
                                      "definition": DEFINITION, "recordings": {}}
    only = [n for n in a.only.split(",") if n]
    todo = [(n, e) for n, e in sorted(manifest["recordings"].items())
            if e["effects"] and (not only or n in only) and (a.redo or n not in out["recordings"])
            and any(x["candidate"] in CANDIDATE_FORMS for x in e["effects"])]
    print(f"{len(todo)} recording(s)", flush=True)
    fitter = Fitter(0.006) if todo else None
    for name, entry in todo:
        if entry["truth_mesh"]["size_m"] != 0.006 or entry["truth_mesh"].get("rim_size_m"):
            sys.exit(f"pseudo_true.py: {name}: truth mesh {entry['truth_mesh']} is not the uniform 6 mm mesh")
        t0 = time.perf_counter()
        res, u_truth = {}, fitter.truth(entry)
        for k, e in enumerate(entry["effects"]):
            if e["candidate"] in CANDIDATE_FORMS:
                res[e["candidate"]] = fitter.fit(entry, k, u_truth)
        out["recordings"][name] = {"seconds": round(time.perf_counter() - t0, 1), "candidates": res}
        out["recordings"] = dict(sorted(out["recordings"].items()))
        write_json_atomic(out_path, out)
        print(name, {c: (f"{v['value']:.4g} (equivalent {v['equivalent']:.4g}, "
                         f"unexplained {v['unexplained_share']:.2f})") for c, v in res.items()},
              f"{out['recordings'][name]['seconds']} s", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
