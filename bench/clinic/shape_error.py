# SPDX-License-Identifier: LGPL-3.0-or-later
"""How well the patient model reproduces a breast's 3D shape (docs/CLINIC.md,
"Figures"). For each of five synthetic patients (`breastsim
synthetic-patient`: a breast that is not a cap - drooping, turned
laterally, fuller in its lateral and lower quadrants - solved standing and
scanned with 0.5 mm noise and two holes) `breastsim patient` takes the
standing scan, its nipple marked, as the left breast: it measures N-IMF, base width, projection
and the ptosis grade on the scan, fits the model to them, and reports the
model's standing skin against the scan's (mean, 95 % and largest distance,
both placed at the fold) and both volumes. The true standing volume (the
synthetic patient's own) shows the scan fit's error apart from the model's.

Usage: /usr/bin/python3 bench/clinic/shape_error.py BIN [OUT]   (about 1 minute)
Writes OUT/shape_error.json and prints the table."""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

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


def one(bin_, out, shape):
    d = os.path.join(out, f"synthetic-{shape['seed']}")
    os.makedirs(d, exist_ok=True)
    opts = [f"--{k}={shape[k]}" for k in ("seed", "volume", "ptosis", "lateral", "asymmetry", "aspect")]
    run([bin_, "-q", "synthetic-patient", *opts, "--noise", "0.0005", "--holes", "2", "--format", "stl",
         "--posture", "standing", "--out", os.path.join(d, "patient")])
    truth = json.load(open(os.path.join(d, "patient", "truth.json")))
    # The nipple marked on the scan (scanner frame, mm), as a scanner's landmark tool gives it;
    # SN-N and the nipple's distance to the midline only place the notch: any plausible values.
    nipple = [1e3 * (a + b) for a, b in zip(truth["loaded"]["nipple_m"], truth["scanner_offset_m"])]
    doc = {"format": "breastsim-patient/1", "id": f"synthetic-{shape['seed']}", "units": "cm",
           "left": {"scan": {"file": "patient/scan.stl", "units": "mm", "nipple": nipple}, "sn_n": 22,
                    "nipple_midline": 12}}
    pf = os.path.join(d, "patient.json")
    json.dump(doc, open(pf, "w"))
    run([bin_, "-q", "patient", pf, "--tolerance", "2", "--out", os.path.join(d, "model")])
    m = json.load(open(os.path.join(d, "model", "patient_model.json")))["sides"][0]
    sc = m["scan"]
    return {"patient": doc["id"], "shape": shape, "measured_mm": sc["measured"],
            "largest_landmark_error_mm": m["largest_error_mm"],
            "model": {"R_mm": 1e3 * m["R_m"], "H_mm": 1e3 * m["H_m"], "stiffness_factor": m["stiffness_factor"]},
            "surface_mm": sc["model_to_scan_mm"], "volume_cm3": {**sc["volume_cm3"],
                                                                 "true": 1e6 * truth["loaded"]["volume_m3"]},
            "volume_error": sc["volume_error"]}


def main():
    bin_ = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else tempfile.mkdtemp()
    rows = [one(bin_, out, s) for s in PATIENTS]
    print("| patient | width, N-IMF, projection [mm] | grade | model R, H [mm] | surface mean / 95 % / max [mm] "
          "| volume model / scan / true [cm3] | volume error |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        lm, m, s, v = r["measured_mm"], r["model"], r["surface_mm"], r["volume_cm3"]
        print(f"| {r['patient']} | {lm['base_width_mm']:.0f}, {lm['n_imf_mm']:.0f}, {lm['projection_mm']:.0f} "
              f"| {lm['ptosis_grade']} | {m['R_mm']:.1f}, {m['H_mm']:.1f} | {s['mean']:.1f} / {s['p95']:.1f} / {s['max']:.1f} "
              f"| {v['model']:.0f} / {v['scan']:.0f} / {v['true']:.0f} | {100 * r['volume_error']:+.1f} % |")
    med = lambda xs: float(np.median(xs))
    print(f"median surface error {med([r['surface_mm']['mean'] for r in rows]):.1f} mm (mean per patient), "
          f"median |volume error| {100 * med([abs(r['volume_error']) for r in rows]):.1f} %")
    json.dump({"rows": rows}, open(os.path.join(out, "shape_error.json"), "w"), indent=1)


if __name__ == "__main__":
    main()
