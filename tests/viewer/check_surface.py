#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Checks on surface_<posture>.json (the skin exported by `simulate`).

  check_surface.py FILE R H [TOL]       vertices on the neutral cap's sphere within TOL
                                        (default 1e-6 m; P2 skins are sampled inside their
                                        curved triangles, off the sphere by the P2 geometry's
                                        error), x >= 0,
                                        outward triangles, displacement field consistent,
                                        flagged as a half model to mirror (mirror_x)
  check_surface.py full FILE            a full breast (no symmetry face): corners of both
                                        signs of x, not flagged to mirror, outward
                                        triangles, displacement field consistent
  check_surface.py same A B TOL         same surface (as sets of triangles by reference
                                        position) and deformed positions within TOL [m]
"""
import json
import sys

import numpy as np


def load(path):
    d = json.load(open(path))
    ref = np.array(d["vertices_ref"]).reshape(-1, 3)
    cur = np.array(d["vertices"]).reshape(-1, 3)
    tri = np.array(d["triangles"]).reshape(-1, 3)
    return d, ref, cur, tri


def check_cap(path, R, H, tol=1e-6):
    d, ref, cur, tri = load(path)
    rs = (R * R + H * H) / (2 * H)  # sphere radius, centre (0, H - rs, 0)
    centre = np.array([0.0, H - rs, 0.0])
    dist = np.linalg.norm(ref - centre, axis=1)
    assert len(tri) > 100, f"{path}: only {len(tri)} triangles"
    assert np.abs(dist - rs).max() < tol, \
        f"{path}: reference vertices off the sphere by {np.abs(dist - rs).max()} m (> {tol})"
    assert ref[:, 0].min() > -1e-9 and ref[:, 1].min() > -1e-9, f"{path}: not the half x, y >= 0"
    assert sorted(set(tri.ravel())) == list(range(len(ref))), f"{path}: unused or bad indices"
    p = ref[tri]
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    outward = np.einsum("ij,ij->i", normal, p.mean(axis=1) - centre)
    assert (outward > 0).all(), f"{path}: {(outward <= 0).sum()} triangles point inwards"
    check_displacement(path, d, ref, cur)
    assert d.get("mirror_x") is True and "half_model" in d, f"{path}: a half model not flagged to mirror"


def check_displacement(path, d, ref, cur):
    disp = np.array(d["fields"]["displacement_mm"])
    assert np.abs(disp - 1e3 * np.linalg.norm(cur - ref, axis=1)).max() < 1e-3
    assert disp.max() > 1.0, f"{path}: no displacement (max {disp.max()} mm)"


def check_full(path):
    """A full breast's skin: star-shaped about the origin (the footprint's
    centre on the chest plane y = 0), so every outward normal has a positive
    radial part."""
    d, ref, cur, tri = load(path)
    assert d.get("mirror_x") is False and "half_model" not in d, \
        f"{path}: a full breast flagged as a half model to mirror"
    assert len(tri) > 100, f"{path}: only {len(tri)} triangles"
    span = ref[:, 0].max() - ref[:, 0].min()
    assert ref[:, 0].min() < -0.2 * span and ref[:, 0].max() > 0.2 * span, \
        f"{path}: x from {ref[:, 0].min()} to {ref[:, 0].max()} m: not the full breast"
    assert ref[:, 1].min() > -1e-9, f"{path}: corners behind the chest plane y = 0"
    assert sorted(set(tri.ravel())) == list(range(len(ref))), f"{path}: unused or bad indices"
    p = ref[tri]
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    outward = np.einsum("ij,ij->i", normal, p.mean(axis=1))
    assert (outward > 0).all(), f"{path}: {(outward <= 0).sum()} triangles point inwards"
    check_displacement(path, d, ref, cur)


def check_same(a, b, tol):
    _, ra, ca, ta = load(a)
    _, rb, cb, tb = load(b)
    key = lambda r: tuple(np.round(1e8 * r).astype(int))
    assert len(ra) == len(rb), f"{a}: {len(ra)} vertices, {b}: {len(rb)}"
    ma = {key(r): c for r, c in zip(ra, ca)}
    mb = {key(r): c for r, c in zip(rb, cb)}
    assert ma.keys() == mb.keys(), "different vertices"
    err = max(np.abs(ma[k] - mb[k]).max() for k in ma)
    assert err <= tol, f"deformed positions differ by {err} m"
    tris = lambda r, t: {frozenset(key(r[i]) for i in x) for x in t}
    assert tris(ra, ta) == tris(rb, tb), "different triangles"


if __name__ == "__main__":
    if sys.argv[1] == "full":
        check_full(sys.argv[2])
    elif sys.argv[1] == "same":
        check_same(sys.argv[2], sys.argv[3], float(sys.argv[4]))
    else:
        check_cap(sys.argv[1], float(sys.argv[2]), float(sys.argv[3]),
                  float(sys.argv[4]) if len(sys.argv) > 4 else 1e-6)
