# SPDX-License-Identifier: LGPL-3.0-or-later
"""The mixed (u, p) formulation (tissue.formulation = mixed): Taylor-Hood,
the displacement of common.py's degree (2) and a continuous pressure of
one degree less.

    w = (u, p) in W = V_u x Q,  u, p = split(w)

Each term's energy is its ENERGY with common.u replaced by the u of w, or,
for a term that declares one, MIXED_ENERGY(u, p) (tissue: the
perturbed-Lagrangian form of eq. (5), stationary in p at p = lambda (J - 1)).
"""
from ufl import Coefficient, FiniteElement, FunctionSpace, MixedElement, TestFunction, TrialFunction
from ufl import replace, split

from common import DEGREE, cell, domain, element, u as u_disp

if DEGREE < 2:
    raise RuntimeError("the mixed formulation is Taylor-Hood: displacement degree >= 2")

W = FunctionSpace(domain, MixedElement([element, FiniteElement("Lagrange", cell, DEGREE - 1)]))
w = Coefficient(W)
q = TestFunction(W)
dw = TrialFunction(W)
u, p = split(w)


def mixed_energy(module):
    """The energy of a term module on the mixed space."""
    if hasattr(module, "MIXED_ENERGY"):
        return module.MIXED_ENERGY(u, p)
    return replace(module.ENERGY, {u_disp: u})


def has_mixed_form(module):
    """Terms with a partner field (a Coefficient in the space of u) have no mixed form."""
    return getattr(module, "PARTNER", None) is None
