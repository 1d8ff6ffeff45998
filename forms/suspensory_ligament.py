# SPDX-License-Identifier: LGPL-3.0-or-later
"""Suspensory (Cooper's) ligaments: the upper pole of the skin is tethered
toward its neutral position by a bed of springs,

    E_lig = int_skin k_l/2 w(X) |u|^2 dA,   w(X) = 1 where Z > 0, else 0,

k_l [Pa/m] per unit reference skin area (docs/MODEL.md frame: Z > 0 is the upper
pole when standing). k_l = 0 reproduces the model without ligaments.
"""
from common import Constant, candidate, domain, dot, ds, u, param, upper_pole

NAME = "suspensory_ligament"
DEFAULT_ON = False
k_l = Constant(domain)

PARAMETERS = {
    "k_l": param("ligament.k", "Pa/m", 2.0e3, 0.0, 1e12,
                 "stiffness of the suspensory ligaments tethering the upper-pole skin (Z > 0)"),
}
CANDIDATE = candidate("ligament.k", "Pa/m", 2e3,
                      "suspensory (Cooper's) ligaments: the upper-pole skin is tethered toward its "
                      "neutral position",
                      sets={"k_l": "q"})

ENERGY = k_l / 2 * upper_pole * dot(u, u) * ds("skin", "surface_quad")
