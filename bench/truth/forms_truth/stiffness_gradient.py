# SPDX-License-Identifier: LGPL-3.0-or-later
"""Hidden effect outside breastsim's candidate library: the tissue's
stiffness varies smoothly across the whole breast, exponentially along one
direction.

    E_grad = int_B (exp(beta (t(X) - t_mean)) - 1) W(F) dV,   W eq. (5),
i.e. mu(X) = mu exp(beta (t(X) - t_mean)), lambda(X) likewise: the
stiffness grows by the factor exp(beta) across the breast along the unit
direction d, and its geometric mean over the volume stays mu. With the
scaled coordinates X_n = (X/R, Y/H, Z/R),

    t(X)   = (d . X_n - t_lo) / (t_hi - t_lo)  in [0, 1] over the breast,
    t_lo, t_hi the least and largest d . X_n over the mesh's nodes,
    t_mean = int_B t dV / V.

d is one of three axes of the breast (pattern "direction"), stiffer toward
its end named second:
    base_apex       d ~ +e_y (soft at the base, stiff at the apex) or its reverse,
    lateral_medial  d ~ -e_x (stiff toward the symmetry plane) or its reverse,
    upper_lower     d ~ -e_z (stiff on the lower pole) or its reverse,
("reverse": sign -1, the other end stiffer), turned by a tilt drawn in
[0, 20] deg toward a random perpendicular direction.

Strength: beta = ln(ratio) [1], ratio the total stiffness ratio across the
breast (exp(beta)); calibrated to the target peak shape change (the
documented physiological span is 2-4; the calibration may end below it,
and the manifest's derived "ratio_across" says where it ended).

No breastsim candidate: family "tissue_field". Closest candidate: none
(gland_core stiffens a central core only).
"""
import math

import numpy as np
import ufl
from dolfinx import fem

NAME = "stiffness_gradient"
FAMILY = "tissue_field"
CANDIDATE = None
CLOSEST = None
STRENGTH = ("beta", "1", 0.5)
REPLACES_FIXED_BASE = False

DIRECTIONS = {"base_apex": (0.0, 1.0, 0.0), "lateral_medial": (-1.0, 0.0, 0.0),
              "upper_lower": (0.0, 0.0, -1.0)}
RANGES = {"tilt_deg": (0.0, 20.0), "tilt_azimuth_deg": (0.0, 360.0)}


def draw_pattern(rng, direction=None, sign=None):
    """direction in DIRECTIONS, sign +1 or -1 (drawn when None)."""
    direction = direction if direction is not None else tuple(DIRECTIONS)[int(rng.integers(len(DIRECTIONS)))]
    if direction not in DIRECTIONS or sign not in (None, 1, -1):
        raise ValueError(f"{NAME}: direction '{direction}' (allowed {tuple(DIRECTIONS)}), sign {sign} (+1 or -1)")
    drawn = 1 if rng.uniform() < 0.5 else -1
    p = {"direction": direction, "sign": sign if sign is not None else drawn}
    p.update({k: round(float(rng.uniform(*r)), 2) for k, r in RANGES.items()})
    return p


def structure(pattern):
    return ()


def unit_direction(pattern):
    """d: the axis (times the sign), turned by the tilt toward the azimuth
    measured in the plane perpendicular to it."""
    a = np.array(DIRECTIONS[pattern["direction"]]) * pattern["sign"]
    helper = np.array([0.0, 0.0, 1.0]) if abs(a[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    p1 = np.cross(a, helper)
    p1 /= np.linalg.norm(p1)
    p2 = np.cross(a, p1)
    az, tilt = math.radians(pattern["tilt_azimuth_deg"]), math.radians(pattern["tilt_deg"])
    d = math.cos(tilt) * a + math.sin(tilt) * (math.cos(az) * p1 + math.sin(az) * p2)
    return d / np.linalg.norm(d)


class Term:
    def __init__(self, ctx, pattern, tissue):
        X = ctx.X
        self.ctx = ctx
        self.beta = ctx.constant()
        self.d = fem.Constant(ctx.mesh, np.zeros(3))       # d / (t_hi - t_lo), in X_n
        self.t0 = ctx.constant()                           # t_lo / (t_hi - t_lo)
        self.t_mean = ctx.constant()
        Xn = ufl.as_vector((X[0] / ctx.R, X[1] / ctx.H, X[2] / ctx.R))
        self.t = ufl.dot(self.d, Xn) - self.t0              # t(X) in [0, 1]
        self.factor = ufl.exp(self.beta * (self.t - self.t_mean))
        self.energy = (self.factor - 1.0) * tissue.density * ctx.dx   # (exp(beta (t - t_mean)) - 1) W
        self.volume = ctx.integrate(ctx.constant(1.0) * ctx.dx)
        self.set_pattern(pattern)

    def set_pattern(self, pattern):
        ctx = self.ctx
        d = unit_direction(pattern)
        x = ctx.mesh.geometry.x
        s = (x[:, 0] / ctx.R) * d[0] + (x[:, 1] / ctx.H) * d[1] + (x[:, 2] / ctx.R) * d[2]
        lo, hi = float(s.min()), float(s.max())
        self.direction = d
        self.d.value = d / (hi - lo)
        self.t0.value = lo / (hi - lo)
        self.t_mean.value = ctx.integrate(self.t * ctx.dx) / self.volume

    def set_strength(self, beta):
        if not (beta > 0 and math.isfinite(beta)):
            raise ValueError(f"{NAME}: beta = {beta} must be > 0")
        self.beta.value = beta

    def describe(self, beta):
        return {"ratio_across": math.exp(beta), "direction_unit": [float(c) for c in self.direction],
                "direction_in": "X_n = (X/R, Y/H, Z/R)", "t_mean": float(self.t_mean.value),
                "stiffness_factor_range": [math.exp(-beta * float(self.t_mean.value)),
                                           math.exp(beta * (1.0 - float(self.t_mean.value)))]}

    def q_equivalent(self, beta):
        return None
