# SPDX-License-Identifier: LGPL-3.0-or-later
"""General tissue-to-tissue suture (knitting condition, docs/MODEL.md eq. (3)):

    f(g(p)) = f(p)   for p on face suture_a, g(p) on face suture_b,
    g(X) = G X + t   (G = tissue_map_matrix row-major, t = tissue_map_shift).

UFL cannot evaluate u at g(X). The partner field w_tissue (a displacement-like
Coefficient in the space of u) holds w = P u: P is the sparse interpolation
matrix, built in C++ (src/model/partner_field.cpp) from the element basis, whose
row for the node X_i of face A evaluates u at g(X_i). Between the nodes w is
interpolated like u, so on face A
    f(g(X)) - f(X) = g(X) + w - X - u.
Penalty with a closure fraction c in [0, 1] (driven like a load, as in
forms/sutures.py): the faces are pulled to the fraction (1 - c) of their
initial offset X - g(X),
    E = k/2 int_A |u - w + c (X - g(X))|^2 dA,
so c = 1 is the knitting condition X + u = g(X) + w up to O(traction / k),
and c = 0 after a reference reset holds the knitted points together.
The derivatives through w = P u are completed in C++ (the chain rule):
    dE/du = E_u + P^T E_w,  d2E/du2 = E_uu + E_uw P + P^T E_wu + P^T E_ww P.
"""
from common import Constant, X, domain, ds, dot, u, V, param
from ufl import Coefficient, as_matrix

NAME = "tissue_suture"
DEFAULT_ON = False
k_tissue_suture = Constant(domain)
tissue_closure = Constant(domain)
tissue_map_matrix = Constant(domain, shape=(9,))
tissue_map_shift = Constant(domain, shape=(3,))
w_tissue = Coefficient(V)

PARAMETERS = {
    "k_tissue_suture": param("tissue_suture.k", "Pa/m", 1.0e7, 0.0, 1e14,
                             "penalty stiffness of the tissue-to-tissue suture (faces suture_a -> suture_b)",
                             lo_open=True),
    "tissue_closure": param("", "1", 1.0, 0.0, 1.0,
                            "closure fraction of the tissue-to-tissue suture (set by the program)"),
    "tissue_map_matrix": param("tissue_suture.map_matrix", "1", [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
                               -1e3, 1e3, "G of the suture map g(X) = G X + t, row-major (3x3)", shape=(9,)),
    "tissue_map_shift": param("tissue_suture.map_shift", "m", [0.0, 0.0, 0.0], -10.0, 10.0,
                              "t of the suture map g(X) = G X + t", shape=(3,)),
}

# The partner field: which Coefficient is w = P u, the faces and the map.
PARTNER = dict(coefficient="w_tissue", face_a="suture_a", face_b="suture_b",
               map_matrix="tissue_map_matrix", map_shift="tissue_map_shift")

_G = as_matrix([[tissue_map_matrix[3 * i + j] for j in range(3)] for i in range(3)])
_gX = _G * X + tissue_map_shift
_gap = u - w_tissue + tissue_closure * (X - _gX)
ENERGY = k_tissue_suture / 2 * dot(_gap, _gap) * ds("suture_a", "surface_quad")
