# SPDX-License-Identifier: LGPL-3.0-or-later
"""Breast tissue: compressible neo-Hookean body (paper eq. 5).

    E_tissue = int_B mu/2 (tr(F F^T) - 3 - 2 ln J) + lambda/2 (J - 1)^2 dV

mixed_density() is the same law in the perturbed-Lagrangian (u, p) form
used by the mixed formulation (tissue.formulation = mixed):

    W(F, p) = mu/2 (tr(F F^T) - 3 - 2 ln J) + p (J - 1) - p^2 / (2 lambda)

dW/dp = 0 gives p = lambda (J - 1), and W(F, lambda (J - 1)) is eq. (5).
"""
from common import Constant, I, det, domain, dx, F, J, fit_alias, grad, neo_hooke, param, tr, ln

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


def mixed_density(Fm, Jm, p, mu_, lmbda_):
    """Perturbed-Lagrangian density of eq. (5) (module docstring); lambda > 0."""
    return mu_ / 2 * (tr(Fm * Fm.T) - 3 - 2 * ln(Jm)) + p * (Jm - 1) - p ** 2 / (2 * lmbda_)


def MIXED_ENERGY(u_, p_):
    """The tissue energy on the mixed space (forms/mixed_forms_common.py)."""
    Fm = I + grad(u_)
    return mixed_density(Fm, det(Fm), p_, mu, lmbda) * dx
