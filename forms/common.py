# SPDX-License-Identifier: LGPL-3.0-or-later
"""Shared UFL objects for every breastsim energy term.

The element degree is chosen by the BREASTSIM_DEGREE environment variable
(set by CMake for each compiled variant). Meshes are isoparametric: the
coordinate element has the same degree as the displacement.

Conventions (docs/MODEL.md): reference (neutral) configuration X, displacement u,
deformed position f(X) = X + u, F = I + grad u.
"""
import os

from ufl import (Coefficient, Constant, FacetNormal, FunctionSpace, Identity, Measure, Mesh,
                 SpatialCoordinate, TestFunction, TrialFunction, VectorElement,
                 conditional, det, dot, grad, gt, inv, ln, outer, sqrt, tetrahedron, tr,
                 variable)

DEGREE = int(os.environ.get("BREASTSIM_DEGREE", "1"))

# Boundary tags (facet markers) shared with the C++ side through the
# generated registry header.
TAGS = {"base": 1, "skin": 2, "symmetry": 3, "suture_abd": 4, "suture_bcd": 5}
# The two faces of the general tissue-to-tissue suture (forms/tissue_suture.py).
TAGS.update({"suture_a": 6, "suture_b": 7})

# Explicit quadrature degrees (the automatic estimate explodes for the
# membrane's inv/ln/sqrt). P1: F is cell-wise constant. P2: F is linear;
# degree 4 is basix's 14-point rule, whose points include the six edge
# midpoints: the energy's log J barrier then acts there too, and the
# inversion check (geometry_forms.py) uses the same points. With the
# 4-point rule (degree 2) P2 cells folded at nodes the energy did not see
# and the suture closure stopped (docs/VERIFICATION.md, "P2 suture closure").
QDEG = {1: {"volume": 1, "volume_load": 2, "surface": 1, "surface_quad": 2},
        2: {"volume": 4, "volume_load": 4, "surface": 2, "surface_quad": 4}}[DEGREE]

cell = tetrahedron
coord_element = VectorElement("Lagrange", cell, DEGREE)
domain = Mesh(coord_element)
element = VectorElement("Lagrange", cell, DEGREE)
# The space must carry the domain: a bare Coefficient(element) would get a
# default affine (P1) domain and the P2 kernels would not match P2 meshes.
V = FunctionSpace(domain, element)

# Unknown displacement and the arguments of residual and Jacobian.
u = Coefficient(V)
v = TestFunction(V)
du = TrialFunction(V)

X = SpatialCoordinate(domain)
upper_pole = conditional(gt(X[2], 0), 1.0, 0.0)   # [Z > 0], the region of the upper-pole terms
N = FacetNormal(domain)          # reference outward normal
I = Identity(3)
F = variable(I + grad(u))        # deformation gradient
J = det(F)

dx = Measure("dx", domain=domain, metadata={"quadrature_degree": QDEG["volume"]})
dx_load = Measure("dx", domain=domain, metadata={"quadrature_degree": QDEG["volume_load"]})


def ds(tag, kind="surface"):
    """Exterior-facet measure on one tagged boundary part."""
    return Measure("ds", domain=domain, subdomain_id=TAGS[tag],
                   metadata={"quadrature_degree": QDEG[kind]})


def outer_np(n):
    """Tangential projector P = I - n (x) n."""
    return I - outer(n, n)


def param(key, unit, default, lo, hi, doc, lo_open=False, shape=()):
    """Metadata of a runtime parameter (a UFL Constant) for the case schema.

    key: the case-file key that sets it; [lo, hi] the allowed range (lo
    excluded when lo_open); shape () for scalars, (n,) for vectors.
    """
    return dict(key=key, unit=unit, default=default, lo=lo, hi=hi, doc=doc,
                lo_open=lo_open, shape=list(shape))


def candidate(parameter, unit, typical, physics, sets, flags=None, family=None, extends=None, default=True):
    """Metadata of a diagnosis candidate (docs/DIAGNOSE.md): the term switched
    on with one scalar q >= 0, nested in the model (q = 0 reproduces the model
    without the term).

    parameter: the reported name of q, e.g. "ligament.k" (or a derived
    quantity such as "base.compliance"); unit; typical: the size of a clearly
    visible effect [unit]; physics: what the term stands for, in plain words.
    sets: {Constant name of the term: rule}, how q sets the case, in order:
    "q" (the parameter = q), "1/q" (= 1/q), "keep_ratio" (keeps its ratio to
    the first one, which is set from q). flags: {case key: bool} set with the
    term switched on (e.g. {"base.fixed": False}); the candidate also applies
    when the term is on but a flag has the other value. family: the physics
    the candidate names when it is found, if another candidate is a
    different form of the same physics (e.g. the ligaments as springs or as
    cables; default: the term's own name). The diagnosis switches on at
    most one form of a family, and two forms of one family that the data
    cannot tell apart still name the family. extends: the candidate this one
    refines (e.g. a regional variation of the skin): it names that
    candidate's physics and applies only where that term is on, so a later
    term must explain the residual better than the found physics' own
    variation does (docs/DIAGNOSE.md); not with family. default: whether a
    diagnosis without --candidates tests it (False: a form kept available
    for --candidates that its out-of-sample test did not admit to the
    default library, docs/DIAGNOSE.md).
    """
    return dict(parameter=parameter, unit=unit, typical=typical, physics=physics,
                sets=dict(sets), flags=dict(flags or {}), family=family, extends=extends, default=default)


def fit_alias(target, role):
    """A short name of `--fit` (calibrate, diagnose) for one parameter.

    target: the Constant name of the term's parameter (in GEOMETRY_FIT: a case
    key); role: "stiffness", "density" or "shape". The role sets the search
    bounds (shape: p0 / 1.25 .. 1.25 p0, else p0 / 30 .. 30 p0) and the
    identifiability rule (a density cannot be fitted with a stiffness: the
    equilibrium depends on their ratio only).
    """
    return dict(target=target, role=role)


# The neutral shape of the mesh belongs to no term: its --fit names.
GEOMETRY_FIT = {"R": fit_alias("geometry.R", "shape"), "H": fit_alias("geometry.H", "shape")}


def neo_hooke(Fm, Jm, mu_, lmbda_, dim):
    """Compressible neo-Hookean density of the paper's eq. (5):
    W = mu/2 (tr(F F^T) - dim - 2 ln J) + lambda/2 (J - 1)^2."""
    return mu_ / 2 * (tr(Fm * Fm.T) - dim - 2 * ln(Jm)) + lmbda_ / 2 * (Jm - 1) ** 2
