# SPDX-License-Identifier: LGPL-3.0-or-later
"""Manufactured solution for nearly incompressible tissue: displacement
against mixed (Taylor-Hood P2-P1) formulation.

Energy: the tissue (paper eq. 5) and the base springs (they hold the rigid
modes that the sliding symmetry leaves free); no skin (the plain membrane
wrinkles under the compression an isochoric field has somewhere).

    displacement:  Pi(u)    = int W(F) dV + E_base(u)
    mixed:         Pi(u, p) = int mu/2 (tr C - 3 - 2 ln J) + p (J - 1) - p^2/(2 lambda) dV
                              + E_base(u)          (tissue.mixed_density)

Weak-form MMS as in verification/forms/mms.py: R(w_h; v) - R(w_ex; v) = 0
with the exact solution w_ex = (u_ex, p_ex), p_ex = lambda (J(u_ex) - 1).
u_ex = curl psi + kappa (mu / lambda) grad phi: the curl part is
divergence-free, the gradient part adds the volumetric strain J - 1 ~ kappa
(mu / lambda) A / L, so that p_ex ~ kappa mu A / L is of the order of the
deviatoric stress, as in a nearly incompressible solid; J - 1 also has the
quadratic part O(|grad u|^2), which adds lambda (A / L)^2 (length scale
L / 2) to p_ex. This is the regime where a displacement discretisation locks
as lambda / mu grows. psi = (psi_1, X psi_2, X psi_3) makes u_x = X (d_y psi_3
- d_z psi_2) vanish on X = 0 (the sliding symmetry), and so does phi, even in
X. Amplitude A, length scale L and kappa are runtime Constants
(|u_ex| ~ A, |grad u_ex| ~ A / L). The exact solution enters the residual
and the errors as this expression evaluated at the quadrature points (no
interpolant).

DEGREE 1: the P1 displacement forms only (the locking comparison).
DEGREE 2: the P2 displacement forms and the P2-P1 mixed forms (coefficient w).
Compiled as its own ffcx module per degree (mms_mixed_p<deg>).
"""
from ufl import Coefficient as _Coefficient
from ufl import Constant as _Constant
from ufl import FiniteElement as _FiniteElement
from ufl import Form as _Form
from ufl import FunctionSpace as _FunctionSpace
from ufl import Measure as _Measure
from ufl import MixedElement as _MixedElement
from ufl import TestFunction as _TestFunction
from ufl import TrialFunction as _TrialFunction
from ufl import as_vector as _as_vector
from ufl import cos as _cos
from ufl import curl as _curl
from ufl import derivative as _derivative
from ufl import det as _det
from ufl import grad as _grad
from ufl import inner as _inner
from ufl import replace as _replace
from ufl import sin as _sin
from ufl import split as _split

import base_springs as _base
import tissue as _tissue
from common import X as _X, I as _I, u, v, du, domain, cell as _cell, element as _element, DEGREE  # noqa: F401
from common import neo_hooke as _neo_hooke
from tissue import mu, lmbda  # noqa: F401  (ffcx names the Constants after these)
from base_springs import c, c_fold_ratio, R_base  # noqa: F401

QDEG_MMS = {1: 4, 2: 6}[DEGREE]
QDEG_ERR = {1: 6, 2: 8}[DEGREE]

# The vector potential [m^2] and the manufactured displacement [m]: its
# amplitude A [m] and length scale L [m] (the wavelength is 2 pi L) are
# runtime Constants (verification/mms_mixed.hpp, IncompressibleMmsSetup).
# The volumetric part kappa (mu / lambda) grad phi (phi even in X: u_x = 0
# on X = 0) gives the pressure a part linear in A, p ~ kappa mu A / L
# (kappa = 0: u_ex divergence-free).
mms_amplitude = _Constant(domain)
mms_length = _Constant(domain)
mms_kappa = _Constant(domain)
_A, _L = mms_amplitude, mms_length
_x, _y, _z = _X[0], _X[1], _X[2]
_psi = _as_vector([_A * _L * _sin(_y / _L) * _cos(_z / _L + 0.3),
                   _x * _A * _cos(_x / _L) * _sin(_z / _L),
                   _x * _A * _sin(_y / _L + 0.2) * _cos(_z / _L)])
_phi = _A * _L * _cos(_x / _L) * _sin(_y / _L + 0.4) * _cos(_z / _L + 0.2)
u_ex = _curl(_psi) + mms_kappa * mu / lmbda * _grad(_phi)
p_ex = lmbda * (_det(_I + _grad(u_ex)) - 1)


def _with_degree(form, q):
    """The same form with every integral at quadrature degree q."""
    return _Form([itg.reconstruct(metadata=dict(itg.metadata(), quadrature_degree=q))
                  for itg in form.integrals()])


_dxq = _Measure("dx", domain=domain, metadata={"quadrature_degree": QDEG_MMS})
_dxe = _Measure("dx", domain=domain, metadata={"quadrature_degree": QDEG_ERR})

# Displacement formulation (u on the vector space of common.py).
_F = _I + _grad(u)
_Rd = _derivative(_neo_hooke(_F, _det(_F), mu, lmbda, 3) * _dxq + _base.ENERGY, u, v)
disp_residual = _with_degree(_Rd - _replace(_Rd, {u: u_ex}), QDEG_MMS)
disp_jacobian = _with_degree(_derivative(_Rd, u, du), QDEG_MMS)
_eu = u - u_ex
disp_error_l2 = _inner(_eu, _eu) * _dxe
disp_error_h1 = _inner(_grad(_eu), _grad(_eu)) * _dxe
norm_l2 = _inner(u_ex, u_ex) * _dxe
norm_h1 = _inner(_grad(u_ex), _grad(u_ex)) * _dxe
forms = [disp_residual, disp_jacobian, disp_error_l2, disp_error_h1, norm_l2, norm_h1]

if DEGREE == 2:
    # Taylor-Hood: P2 displacement, P1 pressure.
    _W = _FunctionSpace(domain, _MixedElement([_element, _FiniteElement("Lagrange", _cell, 1)]))
    w = _Coefficient(_W)
    _q, _dw = _TestFunction(_W), _TrialFunction(_W)
    _u, _p = _split(w)
    _Fm = _I + _grad(_u)
    _Em = (_tissue.mixed_density(_Fm, _det(_Fm), _p, mu, lmbda) * _dxq
           + _replace(_base.ENERGY, {u: _u}))
    _Rm = _derivative(_Em, w, _q)
    _w_ex = _as_vector([u_ex[0], u_ex[1], u_ex[2], p_ex])
    mixed_residual = _with_degree(_Rm - _replace(_Rm, {w: _w_ex}), QDEG_MMS)
    mixed_jacobian = _with_degree(_derivative(_Rm, w, _dw), QDEG_MMS)
    _emu, _emp = _u - u_ex, _p - p_ex
    mixed_error_l2 = _inner(_emu, _emu) * _dxe
    mixed_error_h1 = _inner(_grad(_emu), _grad(_emu)) * _dxe
    mixed_error_p = _emp * _emp * _dxe
    norm_p = p_ex * p_ex * _dxe
    forms += [mixed_residual, mixed_jacobian, mixed_error_l2, mixed_error_h1, mixed_error_p, norm_p]
