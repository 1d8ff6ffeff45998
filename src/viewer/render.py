#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Pictures of breastsim results (headless matplotlib, Agg backend).

Reads the surface_<posture>.json files of a result folder (written by
`breastsim simulate`), mirrors a half model (x >= 0, "mirror_x": true) to the
full breast (a full breast, e.g. a scan, is drawn as it is) and writes
into the output folder (default: the result folder):

  view_<posture>.png   front, side and oblique view, coloured by the
                       displacement magnitude [mm], with a colour bar
  overview.png         every posture side by side (side view), the neutral
                       profile dashed
  compare_<posture>.png  (with --compare OTHER) this folder's and the other
                       folder's shape in the same posture, one row each

Usage: render.py RESULT_DIR [--compare OTHER_DIR] [--size WxH] [--out DIR]
Exit codes: 0 ok, 2 bad input (missing folder/surfaces, bad size), 3
matplotlib missing.
"""
import argparse
import json
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib import cm, colors
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
except ImportError as e:  # pragma: no cover - depends on the machine
    sys.stderr.write(
        f"breastsim pictures: {e}; install Debian's python3-matplotlib and python3-numpy "
        f"(apt-get install python3-matplotlib) for {sys.executable}\n"
    )
    sys.exit(3)

DPI = 100
COLORMAP = "viridis"
# (title, elevation, azimuth) in matplotlib's convention; the model's z is up,
# y points forward (out of the chest), x to the side.
VIEWS = [("front", 0.0, 90.0), ("side", 0.0, 0.0), ("oblique", 20.0, 40.0)]
POSTURE_ORDER = ["standing", "supine", "all_fours", "prone"]


class InputError(Exception):
    pass


def parse_size(text):
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise InputError(f"--size must be WIDTHxHEIGHT in pixels, e.g. 800x600 (got '{text}')")
    if not (100 <= w <= 8000 and 100 <= h <= 8000):
        raise InputError(f"--size {text}: width and height must be in [100, 8000] pixels")
    return w, h


def sagittal_section(ref, tri):
    """The skin's curve in the plane x = 0, ordered around the origin: its
    vertices on the plane and the points where triangle edges cross it."""
    pts = [ref[np.abs(ref[:, 0]) < 1e-6]]
    for a, b in ((0, 1), (1, 2), (2, 0)):
        p, q = ref[tri[:, a]], ref[tri[:, b]]
        cross = p[:, 0] * q[:, 0] < 0
        t = p[cross, 0] / (p[cross, 0] - q[cross, 0])
        pts.append(p[cross] + t[:, None] * (q[cross] - p[cross]))
    prof = np.unique(np.round(np.vstack(pts), 6), axis=0)
    return prof[np.argsort(np.arctan2(prof[:, 2], prof[:, 1]))]


class Surface:
    """The full breast surface of one posture, in mm: a half model
    (mirror_x, the default of older files) with its mirror image x -> -x, a
    full breast as it is."""

    def __init__(self, doc, label):
        self.posture = doc["posture"]
        self.theta = float(doc["theta_deg"])
        self.label = label
        tri = np.asarray(doc["triangles"], dtype=int).reshape(-1, 3)
        ref = 1e3 * np.asarray(doc["vertices_ref"], dtype=float).reshape(-1, 3)
        cur = 1e3 * np.asarray(doc["vertices"], dtype=float).reshape(-1, 3)
        disp = np.asarray(doc["fields"]["displacement_mm"], dtype=float)
        self.mirrored = bool(doc.get("mirror_x", True))
        self.ref, self.cur, self.disp, self.tri = ref, cur, disp, tri
        if self.mirrored:
            n = len(ref)
            mirror = np.array([-1.0, 1.0, 1.0])
            self.ref = np.vstack([ref, ref * mirror])
            self.cur = np.vstack([cur, cur * mirror])
            self.disp = np.concatenate([disp, disp])
            # Mirrored triangles keep pointing outwards with reversed winding.
            self.tri = np.vstack([tri, tri[:, ::-1] + n])
        # The neutral skin's curve in the sagittal plane x = 0 (its side outline).
        self.neutral_profile = sagittal_section(ref, tri)


def load_folder(folder, label=None):
    if not os.path.isdir(folder):
        raise InputError(f"result folder '{folder}' does not exist")
    names = [f for f in os.listdir(folder) if f.startswith("surface_") and f.endswith(".json")]
    if not names:
        raise InputError(
            f"no surface_<posture>.json in '{folder}' (written by `breastsim simulate`)")
    label = label or os.path.basename(os.path.normpath(os.path.abspath(folder)))
    surfaces = []
    for name in names:
        with open(os.path.join(folder, name)) as f:
            surfaces.append(Surface(json.load(f), label))

    def key(s):
        return (POSTURE_ORDER.index(s.posture) if s.posture in POSTURE_ORDER else 99, s.theta)

    return sorted(surfaces, key=key)


def view_direction(elev, azim):
    e, a = np.radians(elev), np.radians(azim)
    return np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])


def shaded_colors(surface, norm, elev, azim):
    """Face colours: colour map of the mean vertex displacement, Lambert
    shading with a head light (plus ambient light)."""
    p = surface.cur[surface.tri]
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-30)
    light = view_direction(elev + 20.0, azim - 25.0)
    lambert = np.clip(normal @ light, 0.0, 1.0)
    shade = 0.5 + 0.5 * lambert
    value = surface.disp[surface.tri].mean(axis=1)
    rgba = cm.get_cmap(COLORMAP)(norm(value))
    rgba[:, :3] *= shade[:, None]
    return rgba


class Frame:
    """Common axis limits so that every picture of a run has the same scale."""

    def __init__(self, surfaces):
        pts = np.vstack([np.vstack([s.cur, s.ref]) for s in surfaces])
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        pad = 0.05 * (hi - lo).max()
        self.lo, self.hi = lo - pad, hi + pad
        vmax = max(float(s.disp.max()) for s in surfaces)
        self.norm = colors.Normalize(vmin=0.0, vmax=max(vmax, 1e-6))


def draw(ax, surface, frame, view, profile=False, zoom=1.35):
    title, elev, azim = view
    face = shaded_colors(surface, frame.norm, elev, azim)
    # Edges in the face colour hide the anti-aliasing seams between triangles.
    poly = Poly3DCollection(surface.cur[surface.tri], facecolors=face, edgecolors=face,
                            linewidths=0.3)
    ax.add_collection3d(poly)
    if profile:
        p = surface.neutral_profile
        ax.plot(p[:, 0], p[:, 1], p[:, 2], "k--", lw=1.0, label="neutral")
    ax.set_xlim(frame.lo[0], frame.hi[0])
    ax.set_ylim(frame.lo[1], frame.hi[1])
    ax.set_zlim(frame.lo[2], frame.hi[2])
    ax.set_box_aspect(frame.hi - frame.lo, zoom=zoom)
    ax.set_proj_type("ortho")
    ax.view_init(elev=elev, azim=azim)
    ax.set_axis_off()
    ax.set_title(title, fontsize=9)


def new_figure(size):
    w, h = size
    return plt.figure(figsize=(w / DPI, h / DPI), dpi=DPI)


def add_colorbar(fig, frame):
    cax = fig.add_axes([0.91, 0.15, 0.018, 0.65])
    bar = fig.colorbar(cm.ScalarMappable(norm=frame.norm, cmap=COLORMAP), cax=cax)
    bar.set_label("displacement [mm]", fontsize=8)
    bar.ax.tick_params(labelsize=7)


def save(fig, path):
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    return path


def posture_title(s):
    return f"{s.posture} (theta = {s.theta:g} deg)"


def grid_figure(rows, size, frame, suptitle, row_labels=None):
    """rows: list of surfaces, one row of the three views each."""
    fig = new_figure(size)
    n = len(rows)
    for r, s in enumerate(rows):
        for c, view in enumerate(VIEWS):
            ax = fig.add_axes([0.01 + 0.30 * c, 0.02 + (n - 1 - r) * 0.9 / n, 0.29, 0.86 / n],
                              projection="3d")
            draw(ax, s, frame, view, profile=view[0] == "side", zoom=1.45 if n == 1 else 1.35)
        if row_labels:
            fig.text(0.01, 0.02 + (n - 0.5 - r) * 0.9 / n, row_labels[r], rotation=90,
                     va="center", fontsize=9)
    fig.suptitle(suptitle, fontsize=11)
    fig.text(0.5, 0.015, "side view: nipple to the right, dashed: neutral shape", ha="center",
             fontsize=8)
    add_colorbar(fig, frame)
    return fig


def render(result_dir, out_dir, size, compare_dir=None):
    surfaces = load_folder(result_dir)
    others = load_folder(compare_dir) if compare_dir else []
    frame = Frame(surfaces + others)
    os.makedirs(out_dir, exist_ok=True)
    written = []
    for s in surfaces:
        fig = grid_figure([s], size, frame, f"{posture_title(s)}: full breast")
        written.append(save(fig, os.path.join(out_dir, f"view_{s.posture}.png")))

    fig = new_figure(size)
    n = len(surfaces)
    for i, s in enumerate(surfaces):
        ax = fig.add_axes([0.01 + i * 0.88 / n, 0.05, 0.86 / n, 0.82], projection="3d")
        draw(ax, s, frame, (posture_title(s), 0.0, 0.0), profile=True, zoom=1.6)
    fig.suptitle("side views (nipple to the right); dashed: neutral shape", fontsize=11)
    add_colorbar(fig, frame)
    written.append(save(fig, os.path.join(out_dir, "overview.png")))

    by_posture = {s.posture: s for s in others}
    for s in surfaces:
        o = by_posture.get(s.posture)
        if o is None:
            continue
        fig = grid_figure([s, o], size, frame, f"{posture_title(s)}: {s.label} vs {o.label}",
                          row_labels=[s.label, o.label])
        written.append(save(fig, os.path.join(out_dir, f"compare_{s.posture}.png")))
    if others and not any(s.posture in by_posture for s in surfaces):
        raise InputError(f"'{result_dir}' and '{compare_dir}' have no posture in common")
    return written


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("result_dir")
    ap.add_argument("--compare", metavar="OTHER_DIR")
    ap.add_argument("--size", default="800x600", help="picture size WxH in pixels")
    ap.add_argument("--out", help="output folder (default: the result folder)")
    a = ap.parse_args(argv)
    try:
        render(a.result_dir, a.out or a.result_dir, parse_size(a.size), a.compare)
    except (InputError, KeyError, ValueError) as e:
        sys.stderr.write(f"breastsim pictures: {e}\n")
        return 2
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except OSError as e:  # a full disk, a folder that cannot be written: one line, no traceback
        sys.stderr.write(f"breastsim pictures: cannot write {e.filename or ''}: {e.strerror or e}\n")
        sys.exit(1)
