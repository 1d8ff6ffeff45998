#!/usr/bin/env python3
"""Where the diagnosis mesh's error sits: the per-point change of the fitted
current model's distances (each fitted on its own mesh) between two
diagnoses of one recording made on different meshes (`breastsim diagnose
... --mesh-size H --max-rounds 1 --candidates skin --mesh-ratio 1`), binned
by the height of the recorded point above the chest plane (y, 10 mm bins),
with the largest single changes.

    python3 bench/truth/mesh_error_by_height.py A/residuals.json B/residuals.json

Reads each diagnosis's residuals.json (`before_mm`: the current model's
distances of round 1, `points_mm`). Prints per posture the RMS change, the
RMS per bin (with its number of points) and the eight largest changes with
their points [mm].
"""
import argparse
import json
import math


def rms(values):
    return math.sqrt(sum(v * v for v in values) / len(values)) if values else 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("coarse", help="residuals.json of the diagnosis on the coarser mesh")
    ap.add_argument("fine", help="residuals.json of the diagnosis on the finer mesh")
    args = ap.parse_args()
    a = json.load(open(args.coarse))
    b = json.load(open(args.fine))
    for pa, pb in zip(a["postures"], b["postures"]):
        change = [x - y for x, y in zip(pa["before_mm"], pb["before_mm"])]
        pts = pa["points_mm"]
        bins = {}
        for v, p in zip(change, pts):
            bins.setdefault(int(p[1] // 10), []).append(v)
        by_height = " ".join(f"y{10 * k}:{rms(vs):.3f}({len(vs)})" for k, vs in sorted(bins.items()))
        print(f"{pa['name']} RMS {rms(change):.3f} mm; by height [mm]: {by_height}")
        top = sorted(range(len(change)), key=lambda i: -abs(change[i]))[:8]
        print("   largest:", " ".join(
            f"{change[i]:+.2f}@({pts[i][0]:.0f},{pts[i][1]:.0f},{pts[i][2]:.0f})" for i in top))


if __name__ == "__main__":
    main()
