# SPDX-License-Identifier: LGPL-3.0-or-later
"""Hidden effect: a stiffer glandular region shaped as a tilted ellipsoid
with a smooth (logistic) edge (breastsim's gland_core: a sharp cylinder
x^2 + z^2 < r_g^2 around the nipple axis).

    E_gland = int_B m chi(X) W(F) dV,   W the tissue density (docs/MODEL.md eq. 5),
    chi(X)  = 1 / (1 + exp((rho(X) - 1) / delta)),
    rho(X)^2 = (d_x/a_x)^2 + (d_y'/a_y)^2 + (d_z'/a_z)^2,  d = X - C,
    d_y' = cos(psi) d_y + sin(psi) d_z,  d_z' = -sin(psi) d_y + cos(psi) d_z
(a rotation about the x axis keeps the region symmetric about x = 0 when
C_x = 0; C_x > 0 means a mirrored pair of lobes in the full breast).

Strength: m (the region is (1 + m) times stiffer at its centre).
Closest breastsim parameter: gland.excess with the same integral of extra
stiffness, m_eq = m int_B chi dV / V_cyl, V_cyl the volume of the half cap
inside breastsim's core x^2 + z^2 < r_g^2 (r_g = gland.radius).
"""
import math

import numpy as np
import ufl
from dolfinx import fem

NAME = "ellipsoid_gland"
CANDIDATE = "gland_core"
STRENGTH = ("m", "1", 3.0)
REPLACES_FIXED_BASE = False

RANGES = {"cx": (0.0, 0.012), "cy": (0.012, 0.032), "cz": (-0.012, 0.015),
          "ax": (0.018, 0.034), "ay": (0.012, 0.024), "az": (0.022, 0.040),
          "psi_deg": (-30.0, 30.0), "delta": (0.08, 0.15)}
R_G_REF = 0.03  # breastsim's gland.radius default (README key table)


def draw_pattern(rng):
    p = {k: round(float(rng.uniform(*r)), 4) for k, r in RANGES.items()}
    if rng.uniform() < 0.6:
        p["cx"] = 0.0  # most glands straddle the symmetry plane
    return p


def structure(pattern):
    return ()


def core_volume(R, H, r_g):
    """Half-cap volume inside x^2 + z^2 < r_g^2:
    V = pi int_0^r_g rho y_top(rho) d rho, y_top = H - Rs + sqrt(Rs^2 - rho^2),
      = pi [ (H - Rs) r_g^2 / 2 + (Rs^3 - (Rs^2 - r_g^2)^(3/2)) / 3 ]."""
    Rs = (R * R + H * H) / (2 * H)
    r = min(r_g, R)
    return math.pi * ((H - Rs) * r * r / 2 + (Rs ** 3 - (Rs * Rs - r * r) ** 1.5) / 3)


class Term:
    def __init__(self, ctx, pattern, tissue, r_g_ref=R_G_REF):
        X = ctx.X
        self.ctx = ctx
        self.m = ctx.constant()
        self.C = fem.Constant(ctx.mesh, np.zeros(3))
        self.inv_axes = fem.Constant(ctx.mesh, np.ones(3))
        self.cos_psi, self.sin_psi = ctx.constant(1.0), ctx.constant()
        self.delta = ctx.constant(0.1)
        d = X - self.C
        dy = self.cos_psi * d[1] + self.sin_psi * d[2]
        dz = -self.sin_psi * d[1] + self.cos_psi * d[2]
        ia = self.inv_axes
        rho = ufl.sqrt((d[0] * ia[0]) ** 2 + (dy * ia[1]) ** 2 + (dz * ia[2]) ** 2)
        self.chi = 1.0 / (1.0 + ufl.exp((rho - 1.0) / self.delta))    # logistic edge
        self.energy = self.m * self.chi * tissue.density * ctx.dx      # m chi W(F)
        self.v_cyl = core_volume(ctx.R, ctx.H, r_g_ref)
        self.r_g_ref = r_g_ref
        self.set_pattern(pattern)

    def set_pattern(self, pattern):
        self.C.value = np.array([pattern["cx"], pattern["cy"], pattern["cz"]])
        self.inv_axes.value = 1.0 / np.array([pattern["ax"], pattern["ay"], pattern["az"]])
        psi = math.radians(pattern["psi_deg"])
        self.cos_psi.value, self.sin_psi.value = math.cos(psi), math.sin(psi)
        self.delta.value = pattern["delta"]
        self.chi_volume = self.ctx.integrate(self.chi * self.ctx.dx)

    def set_strength(self, m):
        if not (m > 0 and math.isfinite(m)):
            raise ValueError(f"{NAME}: m = {m} must be > 0")
        self.m.value = m

    def describe(self, m):
        return {"m": m, "chi_volume_m3": self.chi_volume}

    def q_equivalent(self, m):
        # m_eq = m int chi dV / V_cyl
        return {"candidate": CANDIDATE, "parameter": "gland.excess", "unit": "1",
                "value": m * self.chi_volume / self.v_cyl, "approximate": False,
                "note": f"m int chi dV / V_cyl(r_g = {self.r_g_ref} m), V_cyl = {self.v_cyl:.4g} m^3"}
