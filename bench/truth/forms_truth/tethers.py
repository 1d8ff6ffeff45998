# SPDX-License-Identifier: LGPL-3.0-or-later
"""Hidden effect: suspensory (Cooper's) ligaments as tethers on the skin with
smooth weights around one or two attachment sites (breastsim's
suspensory_ligament term: uniform springs on the whole upper pole Z > 0).

Weight on the skin, sites S_i on the neutral sphere:
    w(X) = sum_i a_i exp(-|X - S_i|^2 / (2 l_i^2)),   a_1 = 1,
    S_i  = c + Rs (sin(al_i) sin(be_i), cos(al_i), sin(al_i) cos(be_i)),
c = (0, H - Rs, 0), al_i the angle from the nipple axis, be_i the azimuth
from the upper pole (+z, be = 0) toward lateral (+x, be = 90 deg).

Two laws (pattern "variant"):
  springs: zero-length springs to the neutral position,
      E = int_skin k/2 w(X) |u|^2 dA;
  cables:  tension-only cables to chest anchors A(X) = (X, 0, Z + d_a),
      E = int_skin k/2 w(X) max(|X + u - A| - |X - A|, 0)^2 dA.

Strength: k [Pa/m] (spring stiffness per unit skin area where w = 1).
Closest breastsim parameter: the uniform ligament.k on Z > 0 with the same
total stiffness, k_eq = k int_skin w dA / A(Z > 0), A(Z > 0) = A_skin / 2 (the
cap is symmetric in z). For cables this is only approximate (a cable resists
only the lengthening toward its anchor).
"""
import math

import numpy as np
import ufl
from dolfinx import fem

NAME = "smooth_tethers"
CANDIDATE = "suspensory_ligament"
STRENGTH = ("k", "Pa/m", 1500.0)
REPLACES_FIXED_BASE = False

RANGES = {"alpha1_deg": (30.0, 65.0), "beta1_deg": (-30.0, 60.0), "ell1": (0.012, 0.022),
          "alpha2_deg": (40.0, 75.0), "beta2_deg": (30.0, 110.0), "ell2": (0.010, 0.020),
          "amp2": (0.0, 0.8), "anchor_dz": (0.015, 0.035)}
VARIANTS = ("springs", "cables")


def draw_pattern(rng, variant=None):
    p = {k: round(float(rng.uniform(*r)), 4) for k, r in RANGES.items()}
    p["variant"] = variant if variant is not None else VARIANTS[int(rng.integers(2))]
    return p


def structure(pattern):
    """The variant selects the law (a different UFL form)."""
    if pattern["variant"] not in VARIANTS:
        raise ValueError(f"{NAME}: variant '{pattern['variant']}' (allowed: {VARIANTS})")
    return (pattern["variant"],)


def site(ctx, alpha_deg, beta_deg):
    """S = c + Rs (sin al sin be, cos al, sin al cos be), c = (0, H - Rs, 0)."""
    al, be = math.radians(alpha_deg), math.radians(beta_deg)
    return np.array([ctx.Rs * math.sin(al) * math.sin(be), ctx.H - ctx.Rs + ctx.Rs * math.cos(al),
                     ctx.Rs * math.sin(al) * math.cos(be)])


class Term:
    def __init__(self, ctx, pattern, tissue=None):
        (self.variant,) = structure(pattern)
        X, u = ctx.X, ctx.u
        self.ctx = ctx
        self.k = ctx.constant()
        self.S = [fem.Constant(ctx.mesh, np.zeros(3)) for _ in range(2)]
        self.ell = [ctx.constant(1.0) for _ in range(2)]
        self.amp2 = ctx.constant()
        self.anchor_dz = ctx.constant()
        w = 0
        for i, amp in ((0, 1.0), (1, self.amp2)):
            d = X - self.S[i]
            w += amp * ufl.exp(-ufl.dot(d, d) / (2 * self.ell[i] ** 2))  # a_i exp(-|X-S_i|^2/(2 l_i^2))
        self.weight = w
        if self.variant == "springs":
            density = 0.5 * self.k * w * ufl.dot(u, u)                    # k/2 w |u|^2
        else:
            A = ufl.as_vector((X[0], 0.0, X[2] + self.anchor_dz))
            L0 = ufl.sqrt(ufl.dot(X - A, X - A))                             # |X - A|
            L = ufl.sqrt(ufl.dot(X + u - A, X + u - A))                      # |X + u - A|
            density = 0.5 * self.k * w * ufl.max_value(L - L0, 0.0) ** 2     # k/2 w <L - L0>^2
        self.energy = density * ctx.ds("skin")
        self.upper_area = 0.5 * ctx.integrate(ctx.constant(1.0) * ctx.ds("skin"))
        self.set_pattern(pattern)

    def set_pattern(self, pattern):
        if structure(pattern) != (self.variant,):
            raise ValueError(f"{NAME}: this term was built for variant '{self.variant}'")
        for i in range(2):
            self.S[i].value = site(self.ctx, pattern[f"alpha{i + 1}_deg"], pattern[f"beta{i + 1}_deg"])
            self.ell[i].value = pattern[f"ell{i + 1}"]
        self.amp2.value = pattern["amp2"]
        self.anchor_dz.value = pattern["anchor_dz"]
        self.weight_integral = self.ctx.integrate(self.weight * self.ctx.ds("skin"))

    def set_strength(self, k):
        if not (k > 0 and math.isfinite(k)):
            raise ValueError(f"{NAME}: k = {k} Pa/m must be > 0")
        self.k.value = k

    def describe(self, k):
        return {"k_Pa_per_m": k, "weight_integral_m2": self.weight_integral,
                "upper_pole_area_m2": self.upper_area}

    def q_equivalent(self, k):
        # k_eq = k int_skin w dA / A(Z > 0)
        note = "k int w dA / A(Z>0)"
        if self.variant == "cables":
            note += "; approximate (cables resist only lengthening toward their anchors)"
        return {"candidate": CANDIDATE, "parameter": "ligament.k", "unit": "Pa/m",
                "value": k * self.weight_integral / self.upper_area, "note": note,
                "approximate": self.variant == "cables"}
