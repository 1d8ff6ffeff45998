# SPDX-License-Identifier: LGPL-3.0-or-later
"""Hidden effect outside breastsim's candidate library: a local stiffening
or softening of the tissue (an inclusion, or a soft fatty region) anywhere
in the breast, with a smooth cosine-squared edge.

    E_incl = int_B A g(X) W(F) dV,   W the tissue density (docs/MODEL.md eq. 5),
i.e. mu(X) = mu (1 + A g(X)) and lambda(X) = lambda (1 + A g(X)): the
tissue is (1 + A) times as stiff at the centre. The bump

    g(X) = cos^2(pi rho / 2) for rho < 1, 0 outside   (C1: g and grad g
           are continuous at rho = 1; not a Gaussian),
    rho^2 = (d'_1/a_1)^2 + (d'_2/a_2)^2 + (d'_3/a_3)^2,   d' = Q^T (X - C),
    Q = R_y(phi) R_x(psi)   (a turn psi about x, then phi about y),
    a_i = s r_i,   r_1 r_2 r_3 = 1   (s the geometric-mean semi-axis),

is an ellipsoid with random axes and orientation; its centre C is drawn in
one of four sites of the breast (RANGES_SITE, m, docs/MODEL.md frame):
    lateral_upper  the lateral upper quadrant (x > 0 lateral, z > 0 cranial),
    lower_pole     the lower pole near the inframammary fold,
    medial         on the symmetry plane x = 0 off the nipple axis (the
                   half model mirrors x < 0, so a site of the medial half
                   of the full breast reads as its mirror; on the plane the
                   region is its own mirror and phi = 0),
    deep           deep near the base (y small).
Contrast 1 + A drawn in [2, 4] (a stiff inclusion) or [0.4, 0.6] (a soft
region).

Strength: the size s [m] (geometric-mean semi-axis; the contrast is part of
the pattern, so the calibration to a target peak shape change sets the
extent). Extent in the manifest ("derived"): semi_axes_m (the support,
g = 0 beyond), half_max_semi_axes_m (g = 1/2 at rho = 1/2), axes_directions
(its rows: Q's columns), region_volume_m3 = int_B g dV; the centre C in
"pattern" (cx, cy, cz) and "derived" centre_m.

No breastsim candidate: family "tissue_field" (a smooth stiffness field
times the tissue). Closest candidate: gland_core / gland_lobe (a stiffer
region on the nipple axis only); a soft region has none.
"""
import math

import numpy as np
import ufl
from dolfinx import fem

NAME = "stiff_inclusion"
FAMILY = "tissue_field"
CANDIDATE = None            # outside the candidate library
CLOSEST = "gland_core"
STRENGTH = ("size", "m", 0.03)
REPLACES_FIXED_BASE = False

SITES = ("lateral_upper", "lower_pole", "medial", "deep")
# centre ranges per site [m]: (cx, cy, cz); every centre lies at least 7 mm
# inside the skin (checked in tests/truth/test_outside_effects.py)
RANGES_SITE = {
    "lateral_upper": {"cx": (0.022, 0.040), "cy": (0.012, 0.028), "cz": (0.012, 0.030)},
    "lower_pole": {"cx": (0.0, 0.020), "cy": (0.006, 0.016), "cz": (-0.046, -0.032)},
    "medial": {"cx": (0.0, 0.0), "cy": (0.012, 0.030), "cz": (0.012, 0.030)},   # cz sign drawn
    "deep": {"cx": (0.0, 0.030), "cy": (0.003, 0.010), "cz": (-0.025, 0.025)},
}
RANGES = {"r1": (0.6, 1.6), "r2": (0.6, 1.6), "r3": (0.6, 1.6),    # axis ratios (normalised)
          "psi_deg": (-40.0, 40.0), "phi_deg": (-40.0, 40.0)}
CONTRAST = {"stiff": (2.0, 4.0), "soft": (0.4, 0.6)}                # 1 + A


def draw_pattern(rng, site=None, kind=None):
    """site in SITES, kind "stiff" or "soft" (drawn when None)."""
    site = site if site is not None else SITES[int(rng.integers(len(SITES)))]
    kind = kind if kind is not None else ("stiff", "soft")[int(rng.integers(2))]
    if site not in SITES or kind not in CONTRAST:
        raise ValueError(f"{NAME}: site '{site}' (allowed {SITES}), kind '{kind}' (allowed {tuple(CONTRAST)})")
    p = {"site": site, "kind": kind}
    for k, r in RANGES_SITE[site].items():
        p[k] = round(float(rng.uniform(*r)), 4)
    if site == "medial" and rng.uniform() < 0.5:
        p["cz"] = -p["cz"]
    r = np.array([rng.uniform(*RANGES[k]) for k in ("r1", "r2", "r3")])
    r = r / np.prod(r) ** (1.0 / 3.0)
    for i in range(3):
        p[f"r{i + 1}"] = round(float(r[i]), 4)
    p["psi_deg"] = round(float(rng.uniform(*RANGES["psi_deg"])), 2)
    p["phi_deg"] = 0.0 if site == "medial" else round(float(rng.uniform(*RANGES["phi_deg"])), 2)
    p["contrast"] = round(float(rng.uniform(*CONTRAST[kind])), 3)
    return p


def structure(pattern):
    return ()


def rotation(psi_deg, phi_deg):
    """Q = R_y(phi) R_x(psi): the ellipsoid's axes are Q's columns."""
    ps, ph = math.radians(psi_deg), math.radians(phi_deg)
    Rx = np.array([[1, 0, 0], [0, math.cos(ps), -math.sin(ps)], [0, math.sin(ps), math.cos(ps)]])
    Ry = np.array([[math.cos(ph), 0, math.sin(ph)], [0, 1, 0], [-math.sin(ph), 0, math.cos(ph)]])
    return Ry @ Rx


def bump(rho2):
    """g = cos^2(pi rho / 2) for rho^2 < 1, else 0 (UFL)."""
    rho = ufl.sqrt(rho2 + 1e-30)
    return ufl.conditional(ufl.lt(rho2, 1.0), ufl.cos(0.5 * math.pi * rho) ** 2, 0.0)


class Term:
    def __init__(self, ctx, pattern, tissue):
        X = ctx.X
        self.ctx = ctx
        self.A = ctx.constant()
        self.C = fem.Constant(ctx.mesh, np.zeros(3))
        # M = Q diag(1/a) : d' / a = M^T (X - C)
        self.M = fem.Constant(ctx.mesh, np.eye(3))
        d = ufl.dot(ufl.transpose(self.M), X - self.C)
        self.g = bump(ufl.dot(d, d))
        self.energy = self.A * self.g * tissue.density * ctx.dx     # A g(X) W(F)
        self.pattern = None
        self.set_pattern(pattern)

    def set_pattern(self, pattern):
        self.pattern = dict(pattern)
        self.C.value = np.array([pattern["cx"], pattern["cy"], pattern["cz"]])
        self.A.value = pattern["contrast"] - 1.0
        self.Q = rotation(pattern["psi_deg"], pattern["phi_deg"])
        self._set_axes(getattr(self, "size", STRENGTH[2]))

    def _set_axes(self, size):
        self.size = size
        self.axes = size * np.array([self.pattern[f"r{i + 1}"] for i in range(3)])
        self.M.value = self.Q @ np.diag(1.0 / self.axes)

    def set_strength(self, size):
        if not (size > 0 and math.isfinite(size)):
            raise ValueError(f"{NAME}: size = {size} m must be > 0")
        self._set_axes(size)

    def describe(self, size):
        self._set_axes(size)
        return {"centre_m": [float(c) for c in self.C.value], "semi_axes_m": [float(a) for a in self.axes],
                "half_max_semi_axes_m": [0.5 * float(a) for a in self.axes],
                "axes_directions": self.Q.T.tolist(), "stiffness_ratio_at_centre": 1.0 + float(self.A.value),
                "region_volume_m3": self.ctx.integrate(self.g * self.ctx.dx), "site": self.pattern["site"]}

    def q_equivalent(self, size):
        return None   # no candidate parameter
