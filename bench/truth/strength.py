# SPDX-License-Identifier: LGPL-3.0-or-later
"""Strength calibration: find the effect strength s whose peak shape change
against the effect-free truth is a target T (mm).

The peak shape change of a set of solves u against the effect-free solves
u_0 is max over postures and skin nodes of |(u - u_0) . n_0| (surface.Skin),
over the skin at least surface.FOLD_BAND above the base.
It grows roughly as a power of s, p(s) ~ a s^k, so the update is a secant
step in log-log coordinates,
    s_new = s (T / p(s))^(1 / k),   k = ln(p_2/p_1) / ln(s_2/s_1)  (k = 1 first),
with k clamped to [0.3, 3] and each step to a factor 30.
"""
import math

TOLERANCE = 0.12     # relative: accept |p / T - 1| <= 12 %


def peak_change(skin, u_ref, u):
    """(max over postures, per-posture max, per-posture rms, max over postures
    including the fold band) in mm; the peaks exclude the fold band
    (surface.FOLD_BAND)."""
    per = [skin.shape_change(a, b) for a, b in zip(u_ref, u)]
    return (max(p[0] for p in per) * 1e3, [p[0] * 1e3 for p in per], [p[1] * 1e3 for p in per],
            max(p[2] for p in per) * 1e3)


def log_slope(history):
    """k from the last two (s, p) pairs, clamped to [0.3, 3]; 1 without two."""
    if len(history) < 2:
        return 1.0
    (s1, p1), (s2, p2) = history[-2], history[-1]
    if s1 == s2 or p1 <= 0 or p2 <= 0:
        return 1.0
    k = math.log(p2 / p1) / math.log(s2 / s1)
    return min(3.0, max(0.3, k))


def next_strength(s, p, target, k):
    """s (T / p)^(1/k), limited to a factor 30 per step."""
    if p <= 0:
        return 30.0 * s
    factor = (target / p) ** (1.0 / k)
    return s * min(30.0, max(1.0 / 30.0, factor))


def calibrate(evaluate, s0, target, max_evals=6, tolerance=TOLERANCE):
    """Secant search; evaluate(s) -> peak [mm]. Returns (s, p, history, k)."""
    if not (target > 0 and s0 > 0):
        raise ValueError(f"calibrate: target = {target} mm and s0 = {s0} must be > 0")
    history, s = [], s0
    for _ in range(max_evals):
        p = evaluate(s)
        history.append((s, p))
        if abs(p / target - 1) <= tolerance:
            break
        s = next_strength(s, p, target, log_slope(history))
    s, p = min(history, key=lambda h: abs(math.log(max(h[1], 1e-12) / target)))
    return s, p, history, log_slope(history)
