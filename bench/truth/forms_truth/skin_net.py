# SPDX-License-Identifier: LGPL-3.0-or-later
"""Hidden effect: skin as a tension-only fibre net of smoothly varying areal
stiffness (a different 2D law from breastsim's neo-Hookean tension-field
membrane).

Three fibre families lie in the reference tangent plane at 60 degrees to
each other, a_f = cos(phi_f) t1 + sin(phi_f) t2, phi_f = phi0 + f 60 deg,
with t1 = P e_z / |P e_z| (P = I - N (x) N) and t2 = N x t1. Each fibre
carries tension only:

    E_skin = int_skin sum_f K(X)/8 max(|F a_f|^2 - 1, 0)^2 dA,
    K(X)   = K_mean * k(X) / <k>_skin,   k(X) = exp(a_y (Y/H - 1/2) + a_z Z/R).

Linearised, the three families make an isotropic membrane with
t mu_s = t lambda_s = 3 K / 8 (sum over the families of (a.eps.a)^2 =
3/8 tr(eps)^2 + 3/4 eps:eps); the closest breastsim skin therefore has
mu_s = 3 K_mean / (8 t_ref), t_ref the case's skin.thickness, with
skin.lambda = skin.mu.

Strength: K_mean [N/m].
"""
import math

import ufl

NAME = "fibre_net_skin"
CANDIDATE = "skin"
STRENGTH = ("K_mean", "N/m", 10.0)
REPLACES_FIXED_BASE = False

RANGES = {"a_y": (-1.0, 1.0), "a_z": (-0.8, 0.8), "phi0_deg": (0.0, 60.0)}
# breastsim's skin thickness in the diagnosis case (cases/default.toml
# skin.thickness); used only for the equivalent mu_s.
T_REF = 0.0015


def draw_pattern(rng):
    return {k: round(float(rng.uniform(*r)), 3) for k, r in RANGES.items()}


def structure(pattern):
    return ()


class Term:
    def __init__(self, ctx, pattern, tissue=None, t_ref=T_REF):
        X, N, F = ctx.X, ctx.N, ctx.F
        self.ctx, self.t_ref = ctx, t_ref
        self.a = {k: ctx.constant() for k in ("a_y", "a_z")}
        self.cos_phi = [ctx.constant() for _ in range(3)]
        self.sin_phi = [ctx.constant() for _ in range(3)]
        self.K_mean = ctx.constant()
        self.inv_mean = ctx.constant(1.0)
        # k(X) = exp(a_y (Y/H - 1/2) + a_z Z/R)
        self.k_shape = ufl.exp(self.a["a_y"] * (X[1] / ctx.H - 0.5) + self.a["a_z"] * X[2] / ctx.R)
        K = self.K_mean * self.k_shape * self.inv_mean
        # tangent frame: t1 = P e_z / |P e_z|, t2 = N x t1
        ez = ufl.as_vector((0.0, 0.0, 1.0))
        Pez = ez - ufl.dot(ez, N) * N
        t1 = Pez / ufl.sqrt(ufl.dot(Pez, Pez))
        t2 = ufl.cross(N, t1)
        density = 0
        for f in range(3):
            a_f = self.cos_phi[f] * t1 + self.sin_phi[f] * t2
            Fa = F * a_f
            # K/8 max(|F a_f|^2 - 1, 0)^2
            density += K / 8 * ufl.max_value(ufl.dot(Fa, Fa) - 1.0, 0.0) ** 2
        self.energy = density * ctx.ds("skin")
        self.area = ctx.integrate(ctx.constant(1.0) * ctx.ds("skin"))
        self.set_pattern(pattern)

    def set_pattern(self, pattern):
        for k in ("a_y", "a_z"):
            self.a[k].value = pattern[k]
        for f in range(3):
            phi = math.radians(pattern["phi0_deg"]) + f * math.pi / 3   # phi_f = phi0 + f 60 deg
            self.cos_phi[f].value = math.cos(phi)
            self.sin_phi[f].value = math.sin(phi)
        self.mean_shape = self.ctx.integrate(self.k_shape * self.ctx.ds("skin")) / self.area
        self.inv_mean.value = 1.0 / self.mean_shape

    def set_strength(self, K_mean):
        if not (K_mean > 0 and math.isfinite(K_mean)):
            raise ValueError(f"{NAME}: K_mean = {K_mean} N/m must be > 0")
        self.K_mean.value = K_mean

    def describe(self, K_mean):
        return {"K_mean_N_per_m": K_mean, "mean_shape": self.mean_shape}

    def q_equivalent(self, K_mean):
        # mu_s = 3 K_mean / (8 t_ref)  (linearised fibre net, see module doc)
        return {"candidate": CANDIDATE, "parameter": "skin.mu", "unit": "Pa",
                "value": 3.0 * K_mean / (8.0 * self.t_ref), "approximate": False,
                "note": f"3 K_mean / (8 t_ref), t_ref = {self.t_ref} m, skin.lambda = skin.mu"}
