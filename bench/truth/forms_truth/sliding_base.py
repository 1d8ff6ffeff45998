# SPDX-License-Identifier: LGPL-3.0-or-later
"""Hidden effect outside breastsim's candidate library: a base that is held
against the chest (u_y = 0 on the base, exact) but slides along it,
restrained by tangential springs that are stiff at the centre of the base
and free at its rim (instead of the fixed base of the baseline truth).

    E_slide = int_base c(X)/2 (a u_x^2 + u_z^2 / a) dA,   u_y = 0 on the base,
    c(X)    = c_mean w(X) / <w>_base,
    w(X)    = w_rim + (1 - w_rim) (1 - r^2/R^2)^n,   r^2 = X^2 + Z^2,

<.>_base the area mean over the base, so c_mean is the area-mean tangential
stiffness; a the anisotropy (lateral x against cranial z). A spring bed
(breastsim's base_springs, c/2 |u|^2 with c uniform or a linear ramp toward
the fold) restrains the normal and the tangential motion alike; this base
has no normal compliance and a tangential stiffness that falls to w_rim
(free for w_rim = 0) at the rim.

Pattern ranges: n in [1, 3], w_rim in [0, 0.1], a in [0.5, 2] (drawn as
ln a uniform in [ln 0.5, ln 2]).

Strength: the mean tangential compliance 1/c_mean [m/Pa] (0: the fixed
base), calibrated to the target peak shape change.

No breastsim candidate: family "base_condition". Closest candidate:
base_springs.
"""
import math

import ufl

NAME = "sliding_base"
FAMILY = "base_condition"
CANDIDATE = None
CLOSEST = "base_springs"
STRENGTH = ("compliance_mean", "m/Pa", 1.5e-6)
REPLACES_FIXED_BASE = True
HOLDS_BASE_NORMAL = True      # solver: u_y = 0 on the base (problem.py)

RANGES = {"n": (1.0, 3.0), "w_rim": (0.0, 0.1), "ln_a": (math.log(0.5), math.log(2.0))}


def draw_pattern(rng):
    p = {"n": round(float(rng.uniform(*RANGES["n"])), 3),
         "w_rim": round(float(rng.uniform(*RANGES["w_rim"])), 3)}
    p["a"] = round(math.exp(float(rng.uniform(*RANGES["ln_a"]))), 3)
    return p


def structure(pattern):
    return ()


def profile(r2_over_R2, n, w_rim):
    """w = w_rim + (1 - w_rim) (1 - r^2/R^2)^n (float or UFL)."""
    return w_rim + (1.0 - w_rim) * (1.0 - r2_over_R2) ** n


class Term:
    def __init__(self, ctx, pattern, tissue=None):
        X, u, R = ctx.X, ctx.u, ctx.R
        self.ctx = ctx
        self.n = ctx.constant(1.0)
        self.w_rim = ctx.constant()
        self.sqrt_a = ctx.constant(1.0)
        self.c_mean = ctx.constant()
        self.inv_mean = ctx.constant(1.0)
        # the base is the disc r <= R: clamp 1 - r^2/R^2 at 0 against round-off at the rim
        s = ufl.max_value(1.0 - (X[0] ** 2 + X[2] ** 2) / R ** 2, 0.0)
        self.w = self.w_rim + (1.0 - self.w_rim) * s ** self.n
        c = self.c_mean * self.w * self.inv_mean
        # c/2 (a u_x^2 + u_z^2 / a)
        self.energy = 0.5 * c * (self.sqrt_a ** 2 * u[0] ** 2 + u[2] ** 2 / self.sqrt_a ** 2) * ctx.ds("base")
        self.area = ctx.integrate(ctx.constant(1.0) * ctx.ds("base"))
        self.set_pattern(pattern)

    def set_pattern(self, pattern):
        self.n.value = pattern["n"]
        self.w_rim.value = pattern["w_rim"]
        self.sqrt_a.value = math.sqrt(pattern["a"])
        self.mean_w = self.ctx.integrate(self.w * self.ctx.ds("base")) / self.area
        self.inv_mean.value = 1.0 / self.mean_w

    def set_strength(self, compliance_mean):
        if not (compliance_mean > 0 and math.isfinite(compliance_mean)):
            raise ValueError(f"{NAME}: compliance_mean = {compliance_mean} m/Pa must be > 0 "
                             "(0 is the fixed base: leave the effect out instead)")
        self.c_mean.value = 1.0 / compliance_mean

    def describe(self, compliance_mean):
        c = 1.0 / compliance_mean
        return {"c_mean_Pa_per_m": c, "mean_w": self.mean_w,
                "c_centre_Pa_per_m": c / self.mean_w, "c_rim_Pa_per_m": c * float(self.w_rim.value) / self.mean_w}

    def q_equivalent(self, compliance_mean):
        return None
