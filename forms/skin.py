"""Skin: a 2D neo-Hookean membrane of thickness t_s on the outer surface.

With the reference normal N and P = I - N (x) N (SPEC.md):
    C_s = P F^T F P,  J_s = |det(F) F^{-T} N|  (area ratio, Nanson),
    W_s = mu_s/2 (tr C_s - 2 - 2 ln J_s) + lambda_s/2 (J_s - 1)^2,
    E_skin = int_skin t_s W_s dA.
Only the tangential part F P of the deformation gradient enters.
"""
from common import (Constant, I, F, J, N, domain, dot, ds, inv, ln, outer_np,
                    param, sqrt, tr)

NAME = "skin"
mu_s = Constant(domain)
lmbda_s = Constant(domain)
t_s = Constant(domain)

PARAMETERS = {
    "mu_s": param("skin.mu", "Pa", 60000.0, 0.0, 1e10, "skin shear modulus"),
    "lmbda_s": param("skin.lambda", "Pa", 60000.0, 0.0, 1e10, "skin first Lame parameter (in-plane)"),
    "t_s": param("skin.thickness", "m", 0.0015, 0.0, 0.05, "skin thickness"),
}

P = outer_np(N)
C_s = P * F.T * F * P
cofN = J * inv(F).T * N
J_s = sqrt(dot(cofN, cofN))
W_s = mu_s / 2 * (tr(C_s) - 2 - 2 * ln(J_s)) + lmbda_s / 2 * (J_s - 1) ** 2

ENERGY = t_s * W_s * ds("skin", "surface")
