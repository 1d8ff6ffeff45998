# SPDX-License-Identifier: LGPL-3.0-or-later
"""How well a model made from four tape measures reproduces a breast's 3D
shape (docs/CLINIC.md, "Figures"). For each of five synthetic patients
(`breastsim synthetic-patient`: a non-cap breast - drooping, turned
laterally, fuller in its lateral and lower quadrants - solved standing,
its skin exact, no noise or holes) the landmarks are measured on its
standing skin as a tape would (base width, N-IMF along the skin in the
nipple's sagittal plane, the ptosis grade), `breastsim patient` fits the
cap model to them, and its standing skin is compared with the patient's:
every patient skin vertex's distance to the model's skin (both placed by
the inframammary fold on the meridian), and the standing volumes.

Usage: /usr/bin/python3 bench/clinic/shape_error.py BIN [OUT]   (about 2 minutes)
Writes OUT/shape_error.json and prints the table."""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy.spatial import cKDTree

PATIENTS = [  # synthetic-patient's shape options
    {"seed": 1, "volume": 400, "ptosis": 0.1, "lateral": 0.0, "asymmetry": 0.05, "aspect": 0.7},
    {"seed": 2, "volume": 500, "ptosis": 0.3, "lateral": 0.1, "asymmetry": 0.15, "aspect": 0.8},
    {"seed": 3, "volume": 650, "ptosis": 0.5, "lateral": -0.1, "asymmetry": 0.25, "aspect": 0.9},
    {"seed": 4, "volume": 800, "ptosis": 0.4, "lateral": 0.2, "asymmetry": 0.1, "aspect": 0.6},
    {"seed": 5, "volume": 1000, "ptosis": 0.6, "lateral": 0.05, "asymmetry": 0.3, "aspect": 1.0},
]


def run(args):
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{' '.join(args)}: exit {r.returncode}\n{r.stderr}")


def read_obj(path, offset_m):
    """Vertices [m, model frame] and triangles of an OBJ scan in mm."""
    v, t = [], []
    for line in open(path):
        w = line.split()
        if w and w[0] == "v":
            v.append([float(x) for x in w[1:4]])
        elif w and w[0] == "f":
            t.append([int(x.split("/")[0]) - 1 for x in w[1:4]])
    return 1e-3 * np.array(v) - np.array(offset_m), np.array(t)


def meridian(v, t, nipple):
    """The skin's section by the plane x = nipple x, from the nipple down to
    where it meets the chest: points in order (the tape of N-IMF)."""
    x0 = nipple[0]
    pts, links = {}, {}
    for tri in t:
        s = v[tri, 0] - x0
        cut = []
        for a, b in ((0, 1), (1, 2), (2, 0)):
            ia, ib = tri[a], tri[b]
            if (s[a] < 0) != (s[b] < 0):
                key = (min(ia, ib), max(ia, ib))
                f = s[a] / (s[a] - s[b])
                pts[key] = v[ia] + f * (v[ib] - v[ia])
                cut.append(key)
        if len(cut) == 2:
            links.setdefault(cut[0], []).append(cut[1])
            links.setdefault(cut[1], []).append(cut[0])
    start = min(pts, key=lambda k: np.linalg.norm(pts[k] - nipple))
    # Walk both ways from the nipple; the branch that ends lower is the lower pole.
    branches = []
    for first in links[start]:
        path, prev, cur = [start], start, first
        while True:
            path.append(cur)
            nxt = [k for k in links[cur] if k != prev]
            if not nxt:
                break
            prev, cur = cur, nxt[0]
        branches.append([pts[k] for k in path])
    lower = min(branches, key=lambda b: b[-1][2])
    return np.array([nipple] + lower[1:])


def ptosis_grade(nipple_below_fold):
    """Regnault (docs/CLINIC.md): 0 more than 1 cm above, 1 within 1 cm, 2 1-3 cm below, 3 more."""
    d = nipple_below_fold
    return 0 if d < -0.01 else 1 if d <= 0.01 else 2 if d <= 0.03 else 3


def landmarks(v, t, nipple):
    tape = meridian(v, t, nipple)
    fold = tape[-1]
    rim = v[v[:, 1] < 5e-4]
    return {"base_width": float(rim[:, 0].max() - rim[:, 0].min()),
            "n_imf": float(np.sum(np.linalg.norm(np.diff(tape, axis=0), axis=1))),
            "ptosis_grade": ptosis_grade(fold[2] - nipple[2]), "fold": fold,
            "projection": float(v[:, 1].max())}


def model_surface(doc, shift):
    """Points on the model's standing skin (mirrored half model), every
    triangle sampled on a barycentric grid of 6 per side, moved by `shift`."""
    v = np.array(doc["vertices"]).reshape(-1, 3)
    t = np.array(doc["triangles"]).reshape(-1, 3)
    v = np.vstack([v, v * [-1, 1, 1]])
    t = np.vstack([t, t + len(v) // 2])
    n = 6
    w = np.array([(i / n, j / n, 1 - (i + j) / n) for i in range(n + 1) for j in range(n + 1 - i)])
    pts = np.einsum("kc,tcd->tkd", w, v[t]).reshape(-1, 3)
    return pts + shift


def one(bin_, out, shape):
    d = os.path.join(out, f"synthetic-{shape['seed']}")
    os.makedirs(d, exist_ok=True)
    opts = [f"--{k}={shape[k]}" for k in ("seed", "volume", "ptosis", "lateral", "asymmetry", "aspect")]
    run([bin_, "-q", "synthetic-patient", *opts, "--noise", "0", "--holes", "0", "--format", "obj",
         "--out", os.path.join(d, "patient")])
    truth = json.load(open(os.path.join(d, "patient", "truth.json")))
    v, t = read_obj(os.path.join(d, "patient", "scan.obj"), truth["scanner_offset_m"])
    nipple = np.array(truth["loaded"]["nipple_m"])
    lm = landmarks(v, t, nipple)
    # SN-N and the nipple's distance to the midline only place the notch: any plausible values.
    doc = {"format": "breastsim-patient/1", "id": f"synthetic-{shape['seed']}", "units": "m",
           "left": {"sn_n": 0.22, "n_imf": lm["n_imf"], "base_width": lm["base_width"],
                    "nipple_midline": max(0.1, 0.6 * lm["base_width"]), "ptosis_grade": lm["ptosis_grade"]}}
    pf = os.path.join(d, "landmarks.json")
    json.dump(doc, open(pf, "w"))
    run([bin_, "-q", "patient", pf, "--tolerance", "2", "--out", os.path.join(d, "model")])
    model = json.load(open(os.path.join(d, "model", "patient_model.json")))["sides"][0]
    run([bin_, "-q", "simulate", os.path.join(d, "model", "case_left.toml"), "--set", "postures.names=standing",
         "--out", os.path.join(d, "standing")])
    surface = json.load(open(os.path.join(d, "standing", "surface_standing.json")))
    summary = json.load(open(os.path.join(d, "standing", "summary.json")))
    # Both skins placed by the fold on the meridian (a point of the chest).
    shift = lm["fold"] - np.array(model["fold_standing_m"])
    shift[1] = 0.0
    dist, _ = cKDTree(model_surface(surface, shift)).query(v)
    vol_model = summary["postures"][0]["volume_m3"]
    vol_truth = truth["loaded"]["volume_m3"]
    return {"patient": doc["id"], "shape": shape,
            "landmarks_mm": {k: 1e3 * lm[k] for k in ("base_width", "n_imf", "projection")},
            "ptosis_grade": lm["ptosis_grade"], "largest_landmark_error_mm": model["largest_error_mm"],
            "model": {"R_mm": 1e3 * model["R_m"], "H_mm": 1e3 * model["H_m"], "stiffness_factor": model["stiffness_factor"],
                      "projection_mm": model["achieved"]["projection_mm"]},
            "surface_mm": {"mean": 1e3 * float(dist.mean()), "p95": 1e3 * float(np.percentile(dist, 95)),
                           "max": 1e3 * float(dist.max())},
            "volume_cm3": {"model": 1e6 * vol_model, "patient": 1e6 * vol_truth},
            "volume_error": (vol_model - vol_truth) / vol_truth}


def main():
    bin_ = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else tempfile.mkdtemp()
    rows = [one(bin_, out, s) for s in PATIENTS]
    print("| patient | width, N-IMF, projection [mm] | grade | model R, H [mm], k | surface mean / 95 % / max [mm] "
          "| volume model / patient [cm3] | volume error |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        lm, m, s, v = r["landmarks_mm"], r["model"], r["surface_mm"], r["volume_cm3"]
        print(f"| {r['patient']} | {lm['base_width']:.0f}, {lm['n_imf']:.0f}, {lm['projection']:.0f} | {r['ptosis_grade']} "
              f"| {m['R_mm']:.1f}, {m['H_mm']:.1f}, {m['stiffness_factor']:.2g} | {s['mean']:.1f} / {s['p95']:.1f} / {s['max']:.1f} "
              f"| {v['model']:.0f} / {v['patient']:.0f} | {100 * r['volume_error']:+.1f} % |")
    med = lambda xs: float(np.median(xs))
    print(f"median surface error {med([r['surface_mm']['mean'] for r in rows]):.1f} mm (mean per patient), "
          f"median |volume error| {100 * med([abs(r['volume_error']) for r in rows]):.1f} %")
    json.dump({"rows": rows}, open(os.path.join(out, "shape_error.json"), "w"), indent=1)


if __name__ == "__main__":
    main()
