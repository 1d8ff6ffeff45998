# SPDX-License-Identifier: LGPL-3.0-or-later
"""Reference benchmark: thick-walled sphere under inner pressure.

An octant of the shell A <= |X| <= B (symmetry planes x = 0, y = 0, z = 0,
sliding), the production tissue energy of forms/tissue.py (paper eq. 5,
compressible neo-Hookean) and a dead inner pressure p0 (nominal traction
t = -p0 N on the inner surface, N the outward reference normal):

    Pi(u) = int_B W(F) dV - int_inner (-p0 N) . u dA
    residual = dPi/du [v],  jacobian = d residual/du [du]

The functionals give the mean radial displacement u . X/|X| on the inner and
outer surfaces (verification/sphere_bench.cpp compares them with the radially
symmetric solution of the same energy, integrated as an ODE).

DEGREE 2 also has the mixed Taylor-Hood P2-P1 forms (coefficient w = (u, p),
the perturbed-Lagrangian tissue of tissue.mixed_density, mixed_*): the same
problem, free of locking as lambda / mu grows (the incompressible limit).

Compiled as its own ffcx module per degree (sphere_bench_p<deg>); not a
registered model term. Facet tags: 1 inner, 2 outer, 3-5 planes x, y, z = 0.
"""
from ufl import Constant as _ConstantU
from ufl import Measure as _Measure
from ufl import derivative as _derivative
from ufl import dot as _dot
from ufl import sqrt as _sqrt
from ufl import Coefficient as _Coefficient
from ufl import FiniteElement as _FiniteElement
from ufl import FunctionSpace as _FunctionSpace
from ufl import MixedElement as _MixedElement
from ufl import TestFunction as _TestFunction
from ufl import TrialFunction as _TrialFunction
from ufl import det as _det
from ufl import grad as _grad
from ufl import split as _split

import tissue as _tissue
from common import X as _X, N as _N, I as _I, u, v, du, domain, DEGREE  # noqa: F401
from common import cell as _cell, dx as _dx, element as _element
from tissue import mu, lmbda  # noqa: F401  (ffcx names the Constants after these)

TAG_INNER, TAG_OUTER = 1, 2
QDEG_SURF = {1: 2, 2: 4}[DEGREE]

p0 = _ConstantU(domain)  # nominal inner pressure [Pa]
_ds = _Measure("ds", domain=domain, metadata={"quadrature_degree": QDEG_SURF})

bench_residual = _derivative(_tissue.ENERGY, u, v) + p0 * _dot(_N, v) * _ds(TAG_INNER)
bench_jacobian = _derivative(bench_residual, u, du)

_er = _X / _sqrt(_dot(_X, _X))  # radial unit vector e_R
bench_ur_inner = _dot(u, _er) * _ds(TAG_INNER)
bench_ur_outer = _dot(u, _er) * _ds(TAG_OUTER)
bench_area_inner = (1 + 0 * _X[0]) * _ds(TAG_INNER)
bench_area_outer = (1 + 0 * _X[0]) * _ds(TAG_OUTER)

forms = [bench_residual, bench_jacobian, bench_ur_inner, bench_ur_outer, bench_area_inner,
         bench_area_outer]

if DEGREE == 2:
    _W = _FunctionSpace(domain, _MixedElement([_element, _FiniteElement("Lagrange", _cell, 1)]))
    w = _Coefficient(_W)
    _q, _dw = _TestFunction(_W), _TrialFunction(_W)
    _u, _p = _split(w)
    _Fm = _I + _grad(_u)
    mixed_residual = (_derivative(_tissue.mixed_density(_Fm, _det(_Fm), _p, mu, lmbda) * _dx, w, _q)
                      + p0 * _dot(_N, _split(_q)[0]) * _ds(TAG_INNER))
    mixed_jacobian = _derivative(mixed_residual, w, _dw)
    mixed_ur_inner = _dot(_u, _er) * _ds(TAG_INNER)
    mixed_ur_outer = _dot(_u, _er) * _ds(TAG_OUTER)
    forms += [mixed_residual, mixed_jacobian, mixed_ur_inner, mixed_ur_outer]
