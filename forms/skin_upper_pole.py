# SPDX-License-Identifier: LGPL-3.0-or-later
"""Upper-pole skin: the skin's own law (forms/skin.py) with moduli added on
the upper pole, Z > 0, where the skin is stiffer or thicker than elsewhere:
    E = int_skin [Z > 0] t_s W_s(F; mu_u, lambda_u) dA,
W_s the relaxed tension-field membrane density of skin.py (same thickness
t_s and tension_only switch); together with the skin term the upper pole
carries mu_s + mu_u, lambda_s + lambda_u.

As a diagnosis candidate it extends skin: it applies only once the skin is
in the model, and it names no new physics. A later candidate that acts on
the same region (e.g. suspensory_cables on the upper-pole skin) is then
named only if it explains the residual better than this regional variation
of the skin already found (docs/DIAGNOSE.md).
"""
from common import Constant, candidate, domain, ds, param, upper_pole
from skin import skin_density, skin_tension_only, t_s

NAME = "skin_upper_pole"
DEFAULT_ON = False
mu_u = Constant(domain)
lmbda_u = Constant(domain)

PARAMETERS = {
    "mu_u": param("skin_upper_pole.mu", "Pa", 20000.0, 0.0, 1e10,
                  "shear modulus added to the skin's on the upper pole (Z > 0)"),
    "lmbda_u": param("skin_upper_pole.lambda", "Pa", 20000.0, 0.0, 1e10,
                     "first Lame parameter (in-plane) added to the skin's on the upper pole"),
}
CANDIDATE = candidate("skin_upper_pole.mu", "Pa", 2e4,
                      "the skin stiffer on the upper pole (Z > 0) than elsewhere",
                      sets={"mu_u": "q", "lmbda_u": "keep_ratio"}, extends="skin")

ENERGY = t_s * upper_pole * skin_density(mu_u, lmbda_u, skin_tension_only) * ds("skin", "surface")
