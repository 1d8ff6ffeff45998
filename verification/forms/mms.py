# SPDX-License-Identifier: LGPL-3.0-or-later
"""Method of manufactured solutions (MMS) for the full breastsim energy.

Weak-form MMS: with the residual R(u; v) = dPi/du [v] of the terms it
exercises (MMS_TERMS: tissue, skin, base springs, each behind its on_<term>
switch as in the model's total) and a smooth displacement u_ex(X),

    find u_h in V_h:  R(u_h; v) - R(u_ex; v) = 0   for all v in V_h,

whose exact solution is u_ex. The load R(u_ex; v) (body force, skin and base
tractions) is derived symbolically by UFL (ufl.replace), so no strong-form
divergence of the membrane stress is needed. The C++ side (verification/mms.cpp)
runs it with every other term off and the plain membrane (skin_tension_only = 0:
the relaxed tension-field energy is only C1, which would spoil the rates).

u_ex has u_x = 0 on x = 0 (compatible with the sliding symmetry constraint): a
uniform dilation of 0.5 % (keeps the skin in tension: the plain membrane
wrinkles at the mesh scale under compression) plus smooth non-polynomial terms
of amplitude 0.3 mm (gradient <= 0.4 %). The strains must stay small: with
the default tissue (lambda / mu = 20) the term lambda J (J - 1) of the tangent
outgrows mu at a few % dilation, the manufactured state (a dead load) is then
unstable and the discrete solutions do not converge (seen with 5 %).

Quadrature: every MMS form uses a higher degree than the production forms
(QDEG_MMS) so that the non-polynomial source term is integrated accurately
enough not to spoil the rates; the error functionals use QDEG_ERR.

Compiled as its own ffcx module per degree (build/generated/mms_p<deg>.py).
"""
from ufl import Form as _Form
from ufl import as_vector as _as_vector
from ufl import cos as _cos
from ufl import derivative as _derivative
from ufl import grad as _grad
from ufl import inner as _inner
from ufl import replace as _replace
from ufl import sin as _sin
from ufl import Measure as _Measure

import importlib as _importlib
from ufl import Constant as _Constant
from common import X as _X, u, v, du, domain, DEGREE  # noqa: F401

# The terms the manufactured solution exercises, each behind its switch
# on_<term> like in the total energy; their Constants are hoisted here (ffcx
# names them after these variables, the C++ side binds them by name).
MMS_TERMS = ("tissue", "skin", "base_springs")
_energy = 0
for _name in MMS_TERMS:
    _m = _importlib.import_module(_name)
    for _k, _obj in vars(_m).items():
        if isinstance(_obj, _Constant) and not _k.startswith("_"):
            globals()[_k] = _obj
    globals()["on_" + _name] = _Constant(domain)
    _energy = _energy + globals()["on_" + _name] * _m.ENERGY

QDEG_MMS = {1: 4, 2: 6}[DEGREE]
QDEG_ERR = {1: 6, 2: 8}[DEGREE]

# The manufactured displacement [m] (module constants, not runtime parameters).
MMS_DILATION = 0.005
MMS_AMPLITUDE = 0.0003
MMS_LENGTH = 0.08
_e, _A, _L = MMS_DILATION, MMS_AMPLITUDE, MMS_LENGTH
_x, _y, _z = _X[0], _X[1], _X[2]
u_ex = _as_vector([_e * _x + _A * _sin(_x / _L) * _cos(_z / _L),
                   _e * _y + _A * _cos(_x / _L) * _sin((_y + _z) / _L),
                   _e * _z + _A * _cos(_y / _L) * _sin(_z / _L + 0.3)])


def _with_degree(form, q):
    """The same form with every integral at quadrature degree q."""
    return _Form([itg.reconstruct(metadata=dict(itg.metadata(), quadrature_degree=q))
                  for itg in form.integrals()])


_R = _derivative(_energy, u, v)
mms_residual = _with_degree(_R - _replace(_R, {u: u_ex}), QDEG_MMS)
mms_jacobian = _with_degree(_derivative(_R, u, du), QDEG_MMS)

_dxe = _Measure("dx", domain=domain, metadata={"quadrature_degree": QDEG_ERR})
_err = u - u_ex
mms_error_l2 = _inner(_err, _err) * _dxe
mms_error_h1 = _inner(_grad(_err), _grad(_err)) * _dxe
mms_norm_l2 = _inner(u_ex, u_ex) * _dxe
mms_norm_h1 = _inner(_grad(u_ex), _grad(u_ex)) * _dxe

# Patch test: a homogeneous deformation (constant F, u_x = 0 on x = 0), which
# P1 (and P2) must reproduce to round-off whatever the mesh.
u_lin = _as_vector([0.004 * _x,
                    0.002 * _x + 0.005 * _y - 0.003 * _z,
                    -0.001 * _x + 0.002 * _y + 0.006 * _z])
patch_residual = _with_degree(_R - _replace(_R, {u: u_lin}), QDEG_MMS)
_err_lin = u - u_lin
patch_error_l2 = _inner(_err_lin, _err_lin) * _dxe
patch_error_h1 = _inner(_grad(_err_lin), _grad(_err_lin)) * _dxe

forms = [mms_residual, mms_jacobian, mms_error_l2, mms_error_h1, mms_norm_l2, mms_norm_h1,
         patch_residual, patch_error_l2, patch_error_h1]
# u_ex at the nodes of the element (basix order: vertices, then edges (2,3),
# (1,3), (1,2), (0,3), (0,2), (0,1)): the Newton initial guess (its interpolant).
_points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
if DEGREE == 2:
    _points += [[0, .5, .5], [.5, 0, .5], [.5, .5, 0], [0, 0, .5], [0, .5, 0], [.5, 0, 0]]
expressions = [(u_ex, _points)]
