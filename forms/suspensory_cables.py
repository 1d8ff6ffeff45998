# SPDX-License-Identifier: LGPL-3.0-or-later
"""Suspensory (Cooper's) ligaments as tension-only cables: each upper-pole
skin point is tied to an anchor on the chest wall that lies d_a above it,

    E_cab = int_skin k_c/2 w(X) max(|x - A| - |X - A|, 0)^2 dA,
    A(X) = (X_x, 0, X_z + d_a),  x = X + u,  w(X) = 1 where Z > 0, else 0,

k_c [Pa/m] per unit reference skin area, d_a [m] the anchor's rise on the
chest wall (y = 0, docs/MODEL.md frame; Z > 0 is the upper pole when standing).
A cable resists only its lengthening: sagging away from the chest and down
is held, moving toward the anchor is free (suspensory_ligament.py is the
zero-length spring form, which resists every displacement). k_c = 0
reproduces the model without the cables. The energy is C1 (its Hessian
jumps where a cable goes taut); the rest length |X - A| >= d_a > 0.
"""
from common import Constant, X, candidate, domain, dot, ds, param, sqrt, u, upper_pole
from ufl import as_vector, max_value

NAME = "suspensory_cables"
DEFAULT_ON = False
k_c = Constant(domain)
d_a = Constant(domain)

PARAMETERS = {
    "k_c": param("cables.k", "Pa/m", 2.0e3, 0.0, 1e12,
                 "stiffness of the tension-only ligament cables from the upper-pole skin (Z > 0) "
                 "to the chest wall"),
    "d_a": param("cables.anchor_rise", "m", 0.02, 1e-3, 0.2,
                 "height of a cable's chest-wall anchor above its skin point"),
}
CANDIDATE = candidate("cables.k", "Pa/m", 2e3,
                      "suspensory (Cooper's) ligaments as tension-only cables from the upper-pole "
                      "skin up to the chest wall",
                      sets={"k_c": "q"}, family="suspensory_ligament")

anchor = as_vector((X[0], 0.0, X[2] + d_a))
rest_length = sqrt(dot(X - anchor, X - anchor))               # |X - A|
length = sqrt(dot(X + u - anchor, X + u - anchor))            # |x - A|
stretch = max_value(length - rest_length, 0.0)                # <|x - A| - |X - A|>
ENERGY = k_c / 2 * upper_pole * stretch ** 2 * ds("skin", "surface_quad")
