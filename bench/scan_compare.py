#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Round-trip numbers of a scanned breast (docs/SCANS.md), in mm.

Usage: scan_compare.py PATIENT MODEL NEUTRAL FORWARD
  PATIENT  synthetic-patient folder (truth.json, reference.msh, scan.*) or "-" (no truth)
  MODEL    scan-model folder (scan.msh, frame.json)
  NEUTRAL  neutral-state folder of MODEL/case.toml (reference.msh, summary.json)
  FORWARD  simulate folder of NEUTRAL/case.reference.toml (surface_<posture>.json)
Prints one JSON line:
  loaded_rms_mm     distance of MODEL's skin nodes (the meshed scan) 2 mm or more off the chest
                    to FORWARD's deformed skin; rim_rms_mm: the same for the nodes nearer the chest
  scan_rms_mm       distance of the scan's points (breast frame) to FORWARD's deformed skin
  reference_rms_mm  distance of NEUTRAL's skin nodes 2 mm or more off the chest to the true
                    reference skin (PATIENT); reference_rim_rms_mm: the nodes nearer the chest
  inverse_residual_mm  the last mismatch RMS of the inverse (NEUTRAL/summary.json)
Distances are exact point-to-triangle distances to the surface, searched
among the triangles around the 8 nearest vertices.
"""
import json, math, os, struct, sys
import numpy as np


def read_msh_skin(path):
    """Nodes and skin triangles (corner nodes) of a gmsh 2.2 ASCII file written by breastsim."""
    lines = open(path).read().split("\n")
    names = {}
    i = lines.index("$PhysicalNames")
    for k in range(int(lines[i + 1])):
        d, t, n = lines[i + 2 + k].split()
        names[n.strip('"')] = int(t)
    i = lines.index("$Nodes")
    n = int(lines[i + 1])
    x = np.array([[float(v) for v in lines[i + 2 + k].split()[1:4]] for k in range(n)])
    j = lines.index("$Elements")
    tris = []
    for k in range(int(lines[j + 1])):
        w = lines[j + 2 + k].split()
        if w[1] in ("2", "9") and int(w[3]) == names["skin"]:
            tris.append([int(v) - 1 for v in w[5:8]])
    return x, np.array(tris)


def read_scan_points(path):
    """Points of a binary STL, an ASCII/binary PLY or an OBJ (as written by breastsim), file units."""
    data = open(path, "rb").read()
    if path.endswith(".stl") and data.startswith(b"solid") and b"facet" in data[:1000]:
        pts = [[float(v) for v in l.split()[1:4]] for l in data.decode().split("\n") if l.strip().startswith("vertex")]
        return np.unique(np.array(pts), axis=0)
    if path.endswith(".stl"):
        n = struct.unpack_from("<I", data, 80)[0]
        pts = [struct.unpack_from("<3f", data, 84 + 50 * t + 12 + 12 * k) for t in range(n) for k in range(3)]
        return np.unique(np.array(pts), axis=0)
    if path.endswith(".obj"):
        return np.array([[float(v) for v in l.split()[1:4]] for l in data.decode().split("\n") if l.startswith("v ")])
    head, _, body = data.partition(b"end_header\n")
    nv = int([l for l in head.decode().split("\n") if l.startswith("element vertex")][0].split()[2])
    if b"binary_little_endian" in head:
        return np.frombuffer(body[:12 * nv], dtype="<f4").reshape(nv, 3).astype(float)
    return np.array([[float(v) for v in l.split()[:3]] for l in body.decode().split("\n")[:nv]])


def point_triangle(p, a, b, c):
    """Distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = ab @ ap, ac @ ap
    if d1 <= 0 and d2 <= 0:
        return np.linalg.norm(ap)
    bp = p - b
    d3, d4 = ab @ bp, ac @ bp
    if d3 >= 0 and d4 <= d3:
        return np.linalg.norm(bp)
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        return np.linalg.norm(ap - d1 / (d1 - d3) * ab)
    cp = p - c
    d5, d6 = ab @ cp, ac @ cp
    if d6 >= 0 and d5 <= d6:
        return np.linalg.norm(cp)
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        return np.linalg.norm(ap - d2 / (d2 - d6) * ac)
    va = d3 * d6 - d5 * d4
    if va <= 0 and (d4 - d3) >= 0 and (d5 - d6) >= 0:
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        return np.linalg.norm(p - (b + w * (c - b)))
    s = 1 / (va + vb + vc)
    return np.linalg.norm(ap - (vb * s) * ab - (vc * s) * ac)


def surface_rms(points, x, tris):
    """RMS distance [same unit] of `points` to the surface (x, tris)."""
    around = [[] for _ in range(len(x))]
    for t, tri in enumerate(tris):
        for v in tri:
            around[v].append(t)
    d2 = []
    for k in range(0, len(points), 500):
        chunk = points[k:k + 500]
        dist = ((chunk[:, None, :] - x[None, :, :]) ** 2).sum(-1)
        near = np.argsort(dist, axis=1)[:, :8]
        for p, vs in zip(chunk, near):
            cand = {t for v in vs for t in around[v]}
            d2.append(min(point_triangle(p, *x[tris[t]]) for t in cand) ** 2)
    return math.sqrt(sum(d2) / len(d2))


def main(patient, model, neutral, forward):
    frame = json.load(open(os.path.join(model, "frame.json")))
    o, E = np.array(frame["origin_m"]), np.array([frame["e_x"], frame["e_y"], frame["e_z"]])
    summary = json.load(open(os.path.join(model, "summary.json")))
    surf = json.load(open(os.path.join(forward, f"surface_{summary['posture']}.json")))
    fx = np.array(surf["vertices"], dtype=float).reshape(-1, 3)
    ft = np.array(surf["triangles"]).reshape(-1, 3)
    mx, mt = read_msh_skin(os.path.join(model, "scan.msh"))
    skin = mx[np.unique(mt)]
    off = skin[:, 1] > 0.002  # the rim on the chest moves with the base springs (not measured by the inverse)
    out = {"loaded_rms_mm": 1e3 * surface_rms(skin[off], fx, ft), "rim_rms_mm": 1e3 * surface_rms(skin[~off], fx, ft)}
    ns = json.load(open(os.path.join(neutral, "summary.json")))
    out["inverse_residual_mm"] = 1e3 * ns["iterations"][-1]["mismatch_rms_m"]
    if patient != "-":
        truth = json.load(open(os.path.join(patient, "truth.json")))
        scan = read_scan_points(os.path.join(patient, truth["scan_file"])) * 1e-3
        out["scan_rms_mm"] = 1e3 * surface_rms((scan - o) @ E.T, fx, ft)
        tx, tt = read_msh_skin(os.path.join(patient, "reference.msh"))
        nx, nt = read_msh_skin(os.path.join(neutral, "reference.msh"))
        shift = np.array([ns.get("reference_shift_x_m", 0.0), 0, 0])
        # neutral (model frame, shifted) -> scanner -> truth breast frame (scanner = truth + offset)
        ref = ((nx[np.unique(nt)] - shift) @ E) + o - np.array(truth["scanner_offset_m"])
        away = (nx[np.unique(nt)] - shift)[:, 1] > 0.002
        out["reference_rms_mm"] = 1e3 * surface_rms(ref[away], tx, tt)
        out["reference_rim_rms_mm"] = 1e3 * surface_rms(ref[~away], tx, tt)
    print(json.dumps({k: round(v, 4) for k, v in out.items()}))


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])
