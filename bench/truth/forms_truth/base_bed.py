# SPDX-License-Identifier: LGPL-3.0-or-later
"""Hidden effect: a non-uniform spring bed under the base (instead of the
fixed base of the baseline truth).

    E_bed = int_base c(X)/2 |u|^2 dA,
    c(X)  = c_mean * s(X) / <s>_base,
    s(X)  = exp(b_z Z/R + b_x X/R + b_r (X^2 + Z^2)/R^2),

<.>_base the area mean over the base, so c_mean is the area-mean stiffness.
The stiffness varies smoothly (a few times between the fold, the upper edge,
the centre and the lateral side); breastsim's base_springs term is uniform
(c_fold_ratio = 1) or a linear ramp toward the fold.

Strength: the mean compliance 1/c_mean [m/Pa] (0: fixed base).
Closest breastsim parameter: base.compliance = 1/c_mean.
"""
import math

import ufl

NAME = "smooth_base_bed"
CANDIDATE = "base_springs"
STRENGTH = ("compliance_mean", "m/Pa", 2e-6)
REPLACES_FIXED_BASE = True

RANGES = {"b_z": (-1.2, 1.2), "b_x": (-0.6, 0.6), "b_r": (-1.0, 1.5)}


def draw_pattern(rng):
    return {k: round(float(rng.uniform(*r)), 3) for k, r in RANGES.items()}


def structure(pattern):
    """Pattern entries that change the UFL (none: every entry is a Constant)."""
    return ()


class Term:
    def __init__(self, ctx, pattern, tissue=None):
        X, R = ctx.X, ctx.R
        self.ctx = ctx
        self.b = {k: ctx.constant() for k in RANGES}
        self.c_mean = ctx.constant()
        self.inv_mean_shape = ctx.constant(1.0)
        # s(X) = exp(b_z Z/R + b_x X/R + b_r (X^2 + Z^2)/R^2)
        self.shape = ufl.exp(self.b["b_z"] * X[2] / R + self.b["b_x"] * X[0] / R
                             + self.b["b_r"] * (X[0] ** 2 + X[2] ** 2) / R ** 2)
        # c(X) = c_mean s(X) / <s>_base
        c_of_X = self.c_mean * self.shape * self.inv_mean_shape
        self.energy = 0.5 * c_of_X * ufl.dot(ctx.u, ctx.u) * ctx.ds("base")
        self.area = ctx.integrate(ctx.constant(1.0) * ctx.ds("base"))
        self.set_pattern(pattern)

    def set_pattern(self, pattern):
        for k in RANGES:
            self.b[k].value = pattern[k]
        self.mean_shape = self.ctx.integrate(self.shape * self.ctx.ds("base")) / self.area
        self.inv_mean_shape.value = 1.0 / self.mean_shape

    def set_strength(self, compliance_mean):
        if not (compliance_mean > 0 and math.isfinite(compliance_mean)):
            raise ValueError(f"{NAME}: compliance_mean = {compliance_mean} m/Pa must be > 0 "
                             "(0 is the fixed base: leave the effect out instead)")
        self.c_mean.value = 1.0 / compliance_mean

    def describe(self, compliance_mean):
        return {"c_mean_Pa_per_m": 1.0 / compliance_mean, "mean_shape": self.mean_shape}

    def q_equivalent(self, compliance_mean):
        return {"candidate": CANDIDATE, "parameter": "base.compliance", "unit": "m/Pa",
                "value": compliance_mean, "approximate": False,
                "note": "1/c_mean, c_mean the area-mean stiffness of the smooth bed"}
