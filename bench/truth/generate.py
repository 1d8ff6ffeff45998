#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Generate the independent-truth benchmark recordings.

    python3 bench/truth/generate.py [--list] [--only NAME[,NAME...]] [--redo]

Needs Debian's python3-dolfinx (0.5.2) and python3-gmsh. Resumable: a
recording whose file exists and has its manifest entry is skipped. Run it
with `nice -n 19`; one process at a time (it writes the manifest).
See bench/truth/README.md for the models and equations.
"""
import argparse
import os
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def ensure_dolfinx():
    """Re-run under Debian's /usr/bin/python3 when the current interpreter
    (e.g. a pyenv shim) has no dolfinx."""
    try:
        import dolfinx  # noqa: F401  (only checked here)
        import gmsh  # noqa: F401
    except ImportError:
        system = "/usr/bin/python3"
        if os.path.exists(system) and os.path.realpath(sys.executable) != os.path.realpath(system):
            os.execv(system, [system] + sys.argv)
        sys.exit("generate.py: needs python3-dolfinx and python3-gmsh "
                 "(apt-get install -y --no-install-recommends python3-dolfinx python3-gmsh)")


ensure_dolfinx()
sys.path.insert(0, str(HERE))

import numpy as np  # noqa: E402

import benchmark_set  # noqa: E402
from forms_truth import EFFECTS, physics_of  # noqa: E402
from geometry import apex_index, build_half_cap  # noqa: E402
from problem import Problems  # noqa: E402
from recording_io import make_recording, read_manifest, write_json_atomic  # noqa: E402
from solver import SolveError  # noqa: E402
from strength import calibrate, log_slope, next_strength, peak_change  # noqa: E402
from surface import FOLD_BAND, Skin  # noqa: E402

R, H = 0.07, 0.06               # cases/default.toml geometry.R, geometry.H
NOISE_SIGMA = 0.0005            # m, per coordinate
P2_TOLERANCE = 0.25             # accept the P2 peak within 25 % of the target
MANIFEST_FORMAT = "breastsim-truth-manifest/1"


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--list", action="store_true", help="list the recordings and their status")
    ap.add_argument("--only", action="append", default=[],
                    help="generate only these recordings (repeatable, comma-separated)")
    ap.add_argument("--redo", action="store_true", help="regenerate existing recordings too")
    ap.add_argument("--out", default=None, help="folder of recordings/ and manifest.json "
                                                 "(default: bench/truth, bench/truth/validation or bench/truth/holdout)")
    ap.add_argument("--mesh-size", type=float, default=0.006, help="truth mesh size [m] (P2)")
    ap.add_argument("--rim-size", type=float, default=None,
                    help="element size at the base rim [m], graded to --mesh-size (default: uniform)")
    ap.add_argument("--chest-wall", type=float, default=None, metavar="K",
                    help="the chest wall as a contact penalty of stiffness K [Pa/m] on the skin "
                         "(forms_truth/chest_contact.py; default: no chest wall)")
    ap.add_argument("--points", type=int, default=2000, help="skin points per posture")
    ap.add_argument("--set", dest="which", choices=benchmark_set.SETS, default="main",
                    help="the benchmark (main), the validation set or the hold-out set "
                         "(default --out: bench/truth, bench/truth/validation, bench/truth/holdout)")
    a = ap.parse_args()
    a.only = [n for item in a.only for n in item.split(",") if n]
    if a.points < 10:
        ap.error("--points must be at least 10 (calibrate/inputs/recording.cpp)")
    if not (0.002 <= a.mesh_size <= 0.02):
        ap.error("--mesh-size must lie in [0.002, 0.02] m")
    if a.rim_size is not None and not (a.mesh_size / 10 <= a.rim_size <= a.mesh_size):
        ap.error(f"--rim-size must lie in [mesh-size/10, mesh-size] = [{a.mesh_size / 10}, {a.mesh_size}] m")
    if a.chest_wall is not None and not (1e5 <= a.chest_wall <= 1e9):
        ap.error(f"--chest-wall K = {a.chest_wall} Pa/m must lie in [1e5, 1e9]")
    return a


class Generator:
    def __init__(self, mesh_size, points, rim_size=None, chest_wall_k=None):
        t0 = time.perf_counter()
        mesh, facets = build_half_cap(R, H, mesh_size, order=2, rim_size=rim_size)
        self.problems = Problems(mesh, facets, R, H, chest_wall_k)
        self.skin = Skin(self.problems.ctx[2])
        V2 = self.problems.ctx[2].V
        self.apex = apex_index(V2, H)
        self.apex_X = V2.tabulate_dof_coordinates()[self.apex]
        self.points = points
        self.mesh_info = {"size_m": mesh_size, "rim_size_m": rim_size, "order": 2, "chest_wall_k_Pa_per_m": chest_wall_k,
                          "tetrahedra": mesh.topology.index_map(3).size_local,
                          "dofs": 3 * V2.dofmap.index_map.size_local, "skin_triangles": len(self.skin.tris)}
        print(f"truth mesh: {self.mesh_info} ({time.perf_counter() - t0:.1f} s)", flush=True)

    # -- solves --------------------------------------------------------------
    def solve(self, degree, spec, effects, strengths, starts=None):
        prob = self.problems.get(degree, effects)
        prob.configure(spec["material"], effects, strengths)
        return prob.solve_postures(spec["postures"], spec["material"]["rho"], starts)

    def peak(self, degree, u_ref, u):
        if degree == 1:
            to2 = self.problems.p1_to_p2
            u_ref, u = [to2(a) for a in u_ref], [to2(b) for b in u]
        return peak_change(self.skin, u_ref, u)

    def calibrate_p1(self, spec, effect, target, u0_1):
        """Strength of one effect alone for the target peak, on the cheap P1
        surrogate (same mesh). Returns (s, p, history, slope, u_effect)."""
        name = effect[0]
        solved = {}

        def evaluate(s):
            start = solved[max(solved)] if solved else u0_1
            solved[s] = self.solve(1, spec, [effect], {name: s}, start)
            return self.peak(1, u0_1, solved[s])[0]

        s, p, hist, k = calibrate(evaluate, EFFECTS[name].STRENGTH[2], target)
        return s, p, hist, k, solved[s]

    def effect_solves(self, spec, u0_1, u0_2):
        """Calibrated P2 solves of the hidden effects; returns (u, strengths, info)."""
        effects = spec["effects"]
        target = spec["target_peak_mm"]
        strengths, info, delta = {}, {}, [np.zeros_like(a) for a in u0_2]
        slope = 1.0
        for eff in effects:
            s, p, hist, slope, u1 = self.calibrate_p1(spec, eff, target, u0_1)
            strengths[eff[0]] = s
            info[eff[0]] = {"p1_history": [[h[0], round(h[1], 4)] for h in hist],
                            "peak_change_alone_p1_mm": round(p, 4)}
            delta = [d + self.problems.p1_to_p2(b - a) for d, a, b in zip(delta, u0_1, u1)]
        u = self.solve(2, spec, effects, strengths, [a + d for a, d in zip(u0_2, delta)])
        peak = self.peak(2, u0_2, u)
        p2_hist = [[dict(strengths), round(peak[0], 4)]]
        if len(effects) == 1:   # correct a single effect on P2 (secant from P1's slope)
            name = effects[0][0]
            for _ in range(2):
                if abs(peak[0] / target - 1) <= P2_TOLERANCE:
                    break
                hist = [(h[0][name], h[1]) for h in p2_hist]
                k = log_slope(hist) if len(hist) > 1 else slope
                strengths[name] = next_strength(strengths[name], peak[0], target, k)
                u = self.solve(2, spec, effects, strengths, u)
                peak = self.peak(2, u0_2, u)
                p2_hist.append([dict(strengths), round(peak[0], 4)])
        return u, strengths, peak, info, p2_hist

    # -- one recording ---------------------------------------------------------
    def sample(self, spec, u):
        rng = np.random.default_rng([spec["seed"], 1])
        out = []
        for p, ui in zip(spec["postures"], u):
            pts = self.skin.sample(ui, self.points, rng)
            pts = pts + rng.normal(0.0, NOISE_SIGMA, pts.shape)          # 0.5 mm noise
            nipple = self.apex_X + ui.reshape(-1, 3)[self.apex] + rng.normal(0.0, NOISE_SIGMA, 3)
            out.append({"name": p["name"], "theta_deg": p["theta_deg"], "points": pts,
                        "nipple": nipple})
        return out

    def generate(self, spec):
        t0 = time.perf_counter()
        stats0 = self._stats()
        u0_2 = self.solve(2, spec, [], {})
        entry = self._entry_head(spec)
        if spec["effects"]:
            u0_1 = self.solve(1, spec, [], {})
            u, strengths, peak, info, p2_hist = self.effect_solves(spec, u0_1, u0_2)
            entry["peak_change_mm"] = round(peak[0], 4)
            entry["peak_change_with_fold_mm"] = round(peak[3], 4)
            entry["peak_above_base_mm"] = 1e3 * FOLD_BAND
            entry["peak_change_per_posture_mm"] = {p["name"]: round(x, 4) for p, x in zip(spec["postures"], peak[1])}
            entry["rms_change_per_posture_mm"] = {p["name"]: round(x, 4) for p, x in zip(spec["postures"], peak[2])}
            entry["p2_history"] = p2_hist
            solved = self.problems.get(2, spec["effects"])
            entry["effects"] = [self._effect_entry(solved, e, strengths[e[0]], info[e[0]])
                                for e in spec["effects"]]
            entry["q_equivalent"] = {e["candidate"]: e["q_equivalent"]["value"] for e in entry["effects"]
                                     if e["q_equivalent"] is not None}
        else:
            u = u0_2
        postures = self.sample(spec, u)
        rec = make_recording(spec["name"], NOISE_SIGMA, {"R": R, "H": H, "rho": spec["material"]["rho"]},
                             postures)
        stats = self._stats()
        entry["solver"] = {k: stats[k] - stats0[k] for k in ("newton", "factorizations")}
        entry["seconds"] = round(time.perf_counter() - t0, 1)
        return rec, entry

    def _stats(self):
        tot = {"newton": 0, "factorizations": 0}
        for prob in self.problems.all():
            for k in tot:
                tot[k] += prob.model.stats[k]
        return tot

    def _entry_head(self, spec):
        m = spec["material"]
        hidden = [physics_of(n) for n, _ in spec["effects"]]
        head = {"name": spec["name"], "file": f"recordings/{spec['name']}.json",
                "hidden": hidden, "hidden_label": "+".join(hidden) if hidden else "none",
                "strength_class": spec["strength_class"], "target_peak_mm": spec["target_peak_mm"],
                "material": {"mu": m["mu"], "lambda": m["lambda"], "lambda_over_mu": m["lambda"] / m["mu"],
                             "rho": m["rho"]},
                "postures": spec["postures"], "seed": spec["seed"], "noise_sigma": NOISE_SIGMA,
                "points_per_posture": self.points, "truth_mesh": self.mesh_info,
                "peak_change_mm": 0.0, "effects": [], "q_equivalent": {}}
        if any(EFFECTS[n].CANDIDATE is None for n, _ in spec["effects"]):
            # effects outside the candidate library: "hidden" names their families
            head["hidden_effects"] = [n for n, _ in spec["effects"]]
            head["outside_library"] = True
        return head

    @staticmethod
    def _effect_entry(problem, effect, s, info):
        name, pattern = effect
        mod = EFFECTS[name]
        term = problem.effects[name]      # pattern set by the last solve
        out = {"model": name, "candidate": mod.CANDIDATE, "pattern": pattern,
               "strength": {"name": mod.STRENGTH[0], "unit": mod.STRENGTH[1], "value": s},
               "derived": term.describe(s), "q_equivalent": term.q_equivalent(s), **info}
        if mod.CANDIDATE is None:    # outside the candidate library
            out.update({"family": mod.FAMILY, "closest_candidate": mod.CLOSEST})
        return out


def generate_with_fallback(gen, spec):
    """One recording; a truth whose Newton solve fails in a reclined posture
    (a crease at the fold, benchmark_set.py) is generated once more with the
    upright set, and its manifest entry says why."""
    try:
        return gen.generate(spec)
    except SolveError as e:
        upright = benchmark_set.upright_postures()
        if spec["postures"] == upright:
            raise
        print(f"{spec['name']}: {e}; again with the upright postures", flush=True)
        rec, entry = gen.generate(dict(spec, postures=upright))
        entry["postures_fallback"] = f"upright set: the reclined truth did not converge ({e})"
        return rec, entry


def status(out, manifest, spec):
    done = manifest is not None and spec["name"] in manifest["recordings"]
    return done and (out / "recordings" / f"{spec['name']}.json").exists()


def main():
    a = parse_args()
    out = Path(a.out) if a.out else (HERE if a.which == "main" else HERE / a.which)
    (out / "recordings").mkdir(parents=True, exist_ok=True)
    specs = benchmark_set.recordings(a.which)
    known = {s["name"] for s in specs}
    unknown = [n for n in a.only if n not in known]
    if unknown:
        sys.exit(f"generate.py: unknown recording(s) {unknown}; see --list")
    manifest = read_manifest(out / "manifest.json") or {
        "format": MANIFEST_FORMAT, "generator": "bench/truth/generate.py", "recordings": {}}
    if a.list:
        for s in specs:
            hidden = "+".join(physics_of(n) for n, _ in s["effects"]) or "none"
            print(f"{s['name']:<40} {s['strength_class']:<8} {hidden:<40} "
                  f"{'done' if status(out, manifest, s) else 'missing'}")
        return 0
    todo = [s for s in specs if (not a.only or s["name"] in a.only)
            and (a.redo or not status(out, manifest, s))]
    print(f"{len(todo)} recording(s) to generate", flush=True)
    if not todo:
        return 0
    gen = Generator(a.mesh_size, a.points, a.rim_size, a.chest_wall)
    failed = []
    for spec in todo:
        print(f"{spec['name']}: ...", flush=True)
        try:
            rec, entry = generate_with_fallback(gen, spec)
        except SolveError as e:
            print(f"{spec['name']}: FAILED ({e})", flush=True)
            failed.append(spec["name"])
            continue
        rec_path = out / "recordings" / f"{spec['name']}.json"
        tmp = rec_path.with_name(f".{rec_path.name}.tmp")
        write_json_atomic(tmp, rec, compact=True)          # recording first (not yet in place),
        manifest["recordings"][spec["name"]] = entry       # then its manifest entry,
        manifest["recordings"] = dict(sorted(manifest["recordings"].items()))
        write_json_atomic(out / "manifest.json", manifest)
        os.replace(tmp, rec_path)                          # then the recording in place
        print(f"{spec['name']}: peak change {entry['peak_change_mm']} mm, "
              f"{entry['seconds']} s, newton {entry['solver']['newton']}", flush=True)
    if failed:
        print(f"failed: {failed} (rerun to retry)")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
