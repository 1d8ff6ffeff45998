#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Plots of a `breastsim calibrate` result (headless matplotlib, Agg backend).

Reads RESULT_DIR/report.json (docs/CALIBRATION.md) and writes into it:

  misfit_history.png  chi2 of every objective evaluation (log scale), by
                      stage (start, fit, corrected fit, uncertainty), the
                      best-so-far line, and the parameters (relative to their
                      starting values) in a second panel
  measurements.png    per measurement: model - measured [mm] before and after
                      the fit, the measurement's sigma as error bars around
                      zero (what "within the noise" means), and the measured
                      value in the label

Usage: calibration_plots.py RESULT_DIR [--size WxH]
Exit codes: 0 ok, 2 bad input (missing report, bad size), 3 matplotlib missing.
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
except ImportError as e:  # pragma: no cover - depends on the machine
    sys.stderr.write(f"breastsim calibration plots: {e}; install Debian's python3-matplotlib "
                     f"and python3-numpy (apt-get install python3-matplotlib)\n")
    sys.exit(3)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from render import DPI, InputError, parse_size  # noqa: E402  (same folder)

STAGE_STYLE = {"start": ("k", "s"), "fit": ("tab:blue", "o"),
               "corrected fit": ("tab:green", "o"), "uncertainty": ("tab:gray", ".")}


def load_report(folder):
    path = os.path.join(folder, "report.json")
    if not os.path.isfile(path):
        raise InputError(f"'{path}' not found (written by `breastsim calibrate`)")
    with open(path) as f:
        return json.load(f)


def history_plot(rep, size, path):
    hist = rep["history"]
    if not hist:
        raise InputError("report.json has an empty 'history'")
    w, h = size
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(w / DPI, h / DPI), dpi=DPI, sharex=True,
                                 gridspec_kw={"height_ratios": [3, 2]})
    ev = np.array([e["evaluation"] for e in hist])
    chi2 = np.array([max(e["chi2"], 1e-300) for e in hist])
    for stage, (col, mk) in STAGE_STYLE.items():
        sel = np.array([e["stage"] == stage for e in hist])
        if sel.any():
            ax.semilogy(ev[sel], chi2[sel], mk, color=col, ms=4, label=stage, ls="none")
    # The best so far, per objective: the corrected fit's chi2 includes the
    # model-error correction, so it starts its own line (Jacobian points excluded).
    label = "best so far"
    for group in (("start", "fit"), ("corrected fit",)):
        sel = np.array([e["stage"] in group for e in hist])
        if sel.any():
            ax.semilogy(ev[sel], np.minimum.accumulate(chi2[sel]), "-", color="tab:red", lw=1.2,
                        label=label)
            label = None
    m = rep["misfit"]["measurements"]
    ax.axhline(m, color="k", ls=":", lw=0.8, label=f"chi2 = m = {m}")
    ax.set_ylabel("chi2")
    ax.legend(fontsize=7, loc="upper right")
    ax.set_title(f"calibration misfit ({rep['algorithm']}): chi2 {rep['misfit']['chi2_before']:.4g}"
                 f" -> {rep['misfit']['chi2_after']:.4g}", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    start = {p["name"]: p["initial"] for p in rep["fit"]}
    for name, p0 in start.items():
        vals = np.array([e["parameters"][name] for e in hist])
        bx.plot(ev, vals / p0, ".-", ms=3, lw=0.8, label=name)
    bx.set_ylabel("parameter / initial")
    bx.set_xlabel("objective evaluation")
    bx.legend(fontsize=7, loc="best", ncol=min(4, len(start)))
    bx.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def measurements_plot(rep, size, path):
    rows = rep["misfit"]["per_measurement"]
    if not rows:
        raise InputError("report.json has no measurements")
    w, h = size
    fig, ax = plt.subplots(figsize=(w / DPI, h / DPI), dpi=DPI)
    n = len(rows)
    y = np.arange(n)[::-1]
    sigma = np.array([1e3 * r["sigma"] for r in rows])
    before = np.array([1e3 * (r["model_before"] - r["measured"]) for r in rows])
    after = np.array([1e3 * (r["model_after"] - r["measured"]) for r in rows])
    ax.errorbar(np.zeros(n), y, xerr=sigma, fmt="|", color="k", ms=10, capsize=3,
                label="measured +- sigma")
    ax.plot(before, y, "x", color="tab:gray", label="model before")
    ax.plot(after, y, "o", color="tab:blue", ms=5, label="model after (fitted)")
    ax.set_yticks(y)
    ax.set_yticklabels([f"{r['measurement']} = {1e3 * r['measured']:.1f}" for r in rows],
                       fontsize=7)
    ax.axvline(0, color="k", lw=0.5)
    span = max(3 * sigma.max(), np.abs(after).max() * 1.2, 1e-3)
    lim = max(span, min(np.abs(before).max() * 1.1, 20 * span))
    ax.set_xlim(-lim, lim)
    ax.set_xlabel("model - measured [mm]   (labels: measured value [mm])")
    ax.set_title(f"measured vs model per measurement (chi2 {rep['misfit']['chi2_before']:.4g} -> "
                 f"{rep['misfit']['chi2_after']:.4g}); points beyond the frame are clipped",
                 fontsize=9)
    ax.legend(fontsize=7, loc="lower right")
    ax.grid(True, axis="x", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("result_dir")
    ap.add_argument("--size", default="800x600", help="picture size WxH in pixels")
    a = ap.parse_args(argv)
    try:
        size = parse_size(a.size)
        rep = load_report(a.result_dir)
        history_plot(rep, size, os.path.join(a.result_dir, "misfit_history.png"))
        measurements_plot(rep, size, os.path.join(a.result_dir, "measurements.png"))
    except (InputError, KeyError, ValueError) as e:
        sys.stderr.write(f"breastsim calibration plots: {e}\n")
        return 2
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except OSError as e:  # a full disk, a folder that cannot be written: one line, no traceback
        sys.stderr.write(f"breastsim calibration plots: cannot write {e.filename or ''}: {e.strerror or e}\n")
        sys.exit(1)
