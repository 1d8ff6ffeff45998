# SPDX-License-Identifier: LGPL-3.0-or-later
"""Tissue stiffness field: the tissue's density (eq. 5) scaled by a smooth,
positive field of the reference position,

    E = int_B (exp(s(X)) - 1) W(F; mu, lambda) dV,
    s(X) = sum_k a_k exp(-|X - c_k|^2 / (2 w^2)),   k = 1 .. K,

so that together with the tissue term the tissue is exp(s(X)) times as
stiff at X: a_k > 0 stiffer, a_k < 0 softer, a = 0 the model without it.
The diagnosis fits the amplitudes a_k on a lattice of centres c_k when no
candidate explains the residual (docs/DIAGNOSE.md, "Field discovery") and
writes what it found as a term file of this form. The defaults are an
example: one region twice as stiff (a_1 = ln 2) at the centre of the
default cap's lower pole.
"""
from common import Constant, X, domain, dx, F, J, neo_hooke, param
from tissue import mu, lmbda
from ufl import as_vector, dot, exp

NAME = "tissue_field"
DEFAULT_ON = False
K = 24  # basis functions (unused ones: a_k = 0)
a_field = Constant(domain, shape=(K,))
c_field = Constant(domain, shape=(3 * K,))
w_field = Constant(domain)

_example_centres = [0.02, 0.02, -0.02] + [0.0, 0.0, 0.0] * (K - 1)
PARAMETERS = {
    "a_field": param("tissue_field.amplitudes", "1", [0.6931471805599453] + [0.0] * (K - 1), -5.0, 5.0,
                     "amplitude a_k of each basis function of s(X): the tissue is exp(s(X)) x as stiff",
                     shape=(K,)),
    "c_field": param("tissue_field.centres", "m", _example_centres, -10.0, 10.0,
                     "centre c_k of each basis function (x, y, z of each in turn)", shape=(3 * K,)),
    "w_field": param("tissue_field.width", "m", 0.015, 0.0, 1.0,
                     "width w of the Gaussian basis functions", lo_open=True),
}


def basis(k):
    """exp(-|X - c_k|^2 / (2 w^2))."""
    d = X - as_vector([c_field[3 * k], c_field[3 * k + 1], c_field[3 * k + 2]])
    return exp(-dot(d, d) / (2 * w_field ** 2))


s_field = sum(a_field[k] * basis(k) for k in range(K))
ENERGY = (exp(s_field) - 1) * neo_hooke(F, J, mu, lmbda, 3) * dx
