# SPDX-License-Identifier: LGPL-3.0-or-later
"""Skin: a 2D neo-Hookean membrane of thickness t_s on the outer surface.

With the reference normal N and P = I - N (x) N (docs/MODEL.md):
    C_s = P F^T F P,  J_s = |det(F) F^{-T} N|  (area ratio, Nanson),
    W_s = mu_s/2 (tr C_s - 2 - 2 ln J_s) + lambda_s/2 (J_s - 1)^2,
    E_skin = int_skin t_s W_s dA.
Only the tangential part F P of the deformation gradient enters.

A membrane has no bending stiffness: under in-plane compression the plain
law above has negative geometric stiffness and wrinkles at the mesh scale
(Newton stalls, the solution is not unique). With skin_tension_only = 1
(default) the relaxed tension-field energy is used instead (thin skin wrinkles
rather than carrying compression). In principal stretches l1 >= l2
(l1^2 = (I1 + sqrt(I1^2 - 4 J_s^2)) / 2, l2 = J_s / l1):
    taut     (l2 >= n(l1)):      W_s(l1, l2)
    wrinkled (l1 > 1, l2 < n):   W_s(l1, n(l1))      (stress-free across the wrinkles)
    slack    (l1 <= 1):          0
where n(l1) is the natural width, dW_s/dl2 = 0:
    n = (L l1 + sqrt(L^2 l1^2 + 4 mu (mu + L l1^2))) / (2 (mu + L l1^2)).
The relaxed energy is C1 and equals W_s wherever the skin is in tension.
"""
from common import (Constant, F, J, N, candidate, domain, dot, ds, fit_alias, inv, ln,
                    outer_np, param, sqrt, tr)
from ufl import conditional, gt, lt, max_value

NAME = "skin"
mu_s = Constant(domain)
lmbda_s = Constant(domain)
t_s = Constant(domain)
skin_tension_only = Constant(domain)

PARAMETERS = {
    "mu_s": param("skin.mu", "Pa", 20000.0, 0.0, 1e10, "skin shear modulus"),
    "lmbda_s": param("skin.lambda", "Pa", 20000.0, 0.0, 1e10, "skin first Lame parameter (in-plane)"),
    "t_s": param("skin.thickness", "m", 0.0015, 0.0, 0.05, "skin thickness"),
    "skin_tension_only": param("skin.tension_only", "1", 1.0, 0.0, 1.0,
                               "1: relaxed tension-field membrane (wrinkles, no compression); "
                               "0: plain neo-Hookean membrane"),
}
FIT = {"mu_s": fit_alias("mu_s", "stiffness"), "lambda_s": fit_alias("lmbda_s", "stiffness")}
CANDIDATE = candidate("skin.mu", "Pa", 2e4,
                      "a skin membrane (mu_s, lambda_s, thickness) on the outer surface",
                      sets={"mu_s": "q", "lmbda_s": "keep_ratio"})


def membrane_density(mu, lmbda, l1, l2):
    """W_s in principal stretches."""
    return mu / 2 * (l1 ** 2 + l2 ** 2 - 2 - 2 * ln(l1 * l2)) + lmbda / 2 * (l1 * l2 - 1) ** 2


def skin_density(mu, lmbda, tension_only):
    """W_s per unit reference volume of skin with moduli (mu, lmbda): the
    relaxed tension-field law where tension_only > 0.5, else the plain one."""
    P = outer_np(N)
    C_s = P * F.T * F * P
    cofN = J * inv(F).T * N
    J_s = sqrt(dot(cofN, cofN))
    I1 = tr(C_s)
    W_plain = mu / 2 * (I1 - 2 - 2 * ln(J_s)) + lmbda / 2 * (J_s - 1) ** 2
    # Principal stretches. Where they (nearly) coincide, d = (l1^2 - l2^2)^2 < 1e-10,
    # the eigen-decomposition is singular; there the state is either taut or (for
    # equibiaxial compression) slack, and the plain law is used: exact at the
    # identity (zero stress, no round-off amplification) and taut states.
    disc = I1 ** 2 - 4 * J_s ** 2
    disc_safe = max_value(disc, 1e-10)
    l1 = sqrt((I1 + sqrt(disc_safe)) / 2)
    l2 = J_s / l1
    natural = (lmbda * l1 + sqrt(lmbda ** 2 * l1 ** 2 + 4 * mu * (mu + lmbda * l1 ** 2))) \
        / (2 * (mu + lmbda * l1 ** 2))
    W_relaxed = conditional(gt(disc, 1e-10),
                            conditional(gt(l1, 1.0),
                                        conditional(lt(l2, natural), membrane_density(mu, lmbda, l1, natural),
                                                    W_plain),
                                        0.0),
                            W_plain)
    return conditional(gt(tension_only, 0.5), W_relaxed, W_plain)


W_s = skin_density(mu_s, lmbda_s, skin_tension_only)

ENERGY = t_s * W_s * ds("skin", "surface")
