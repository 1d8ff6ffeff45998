"""Breast tissue: compressible neo-Hookean body (paper eq. 5).

    E_tissue = int_B mu/2 (tr(F F^T) - 3 - 2 ln J) + lambda/2 (J - 1)^2 dV
"""
from common import Constant, domain, dx, F, J, fit_alias, neo_hooke, param

NAME = "tissue"
mu = Constant(domain)
lmbda = Constant(domain)

PARAMETERS = {
    "mu": param("tissue.mu", "Pa", 400.0, 0.0, 1e8, "tissue shear modulus", lo_open=True),
    "lmbda": param("tissue.lambda", "Pa", 8000.0, 0.0, 1e10,
                   "tissue first Lame parameter (volumetric stiffness)"),
}
FIT = {"mu": fit_alias("mu", "stiffness"), "lambda": fit_alias("lmbda", "stiffness")}

ENERGY = neo_hooke(F, J, mu, lmbda, 3) * dx
