# SPDX-License-Identifier: LGPL-3.0-or-later
"""Residual maps of a breastsim diagnosis.

Usage: python3 diagnose_plots.py RESULT_DIR [OUT_DIR]

Reads RESULT_DIR/residuals.json (written by `breastsim diagnose`) and writes
into OUT_DIR (default RESULT_DIR)
  residuals_<posture>.png  recorded points coloured by the normal distance to
                           the simulated skin [mm], before (current model)
                           and after (with the discovered physics), front
                           view (x-z, mirrored to the full breast) and side
                           view (y-z); blue: recording inside the model, red:
                           outside; the colour range is the same before/after
  residual_rms.png         RMS distance per posture before/after and the noise
"""
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def residual_map(p, noise, out):
    pts = np.asarray(p["points_mm"])
    before = np.asarray(p["before_mm"])
    after = np.asarray(p["after_mm"])
    lim = max(3 * noise, float(np.percentile(np.abs(before), 99)))
    fig, axes = plt.subplots(2, 2, figsize=(10, 8), dpi=100, constrained_layout=True)
    for row, (label, r, rms) in enumerate([("before", before, p["rms_before_mm"]),
                                           ("after", after, p["rms_after_mm"])]):
        # Front view: the full breast, mirrored across the symmetry plane x = 0.
        ax = axes[row][0]
        sc = ax.scatter(np.concatenate([pts[:, 0], -pts[:, 0]]), np.concatenate([pts[:, 2], pts[:, 2]]),
                        c=np.concatenate([r, r]), cmap="RdBu_r", vmin=-lim, vmax=lim, s=9)
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("z [mm] (cranial)")
        ax.set_title(f"{p['name']} {label}: front, RMS {rms:.3f} mm")
        ax = axes[row][1]
        order = np.argsort(pts[:, 0])[::-1]  # near the symmetry plane drawn last (on top)
        ax.scatter(pts[order, 1], pts[order, 2], c=r[order], cmap="RdBu_r", vmin=-lim, vmax=lim, s=9)
        ax.set_aspect("equal")
        ax.set_xlabel("y [mm] (projection)")
        ax.set_title(f"{p['name']} {label}: side")
    cb = fig.colorbar(sc, ax=axes, shrink=0.8)
    cb.set_label(f"recording - model, normal distance [mm] (noise {noise:.2f} mm)")
    fig.savefig(out)
    plt.close(fig)


def rms_chart(doc, out):
    names = [p["name"] for p in doc["postures"]]
    x = np.arange(len(names))
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=100, constrained_layout=True)
    ax.bar(x - 0.2, [p["rms_before_mm"] for p in doc["postures"]], 0.4, label="current model")
    found = ", ".join(doc["discovered"]) or "nothing found"
    ax.bar(x + 0.2, [p["rms_after_mm"] for p in doc["postures"]], 0.4, label=f"after ({found})")
    ax.axhline(doc["noise_sigma_mm"], color="k", ls="--", label="noise sigma")
    ax.set_xticks(x, names)
    ax.set_ylabel("RMS normal distance [mm]")
    ax.set_title("Fit to the recording")
    ax.legend()
    fig.savefig(out)
    plt.close(fig)


def main():
    if len(sys.argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        return 2
    d = Path(sys.argv[1])
    out = Path(sys.argv[2]) if len(sys.argv) == 3 else d
    doc = json.loads((d / "residuals.json").read_text())
    for p in doc["postures"]:
        residual_map(p, doc["noise_sigma_mm"], out / f"residuals_{p['name']}.png")
    rms_chart(doc, out / "residual_rms.png")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except OSError as e:  # a full disk, a folder that cannot be written: one line, no traceback
        sys.stderr.write(f"breastsim diagnose plots: cannot write {e.filename or ''}: {e.strerror or e}\n")
        sys.exit(1)
