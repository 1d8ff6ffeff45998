# SPDX-License-Identifier: LGPL-3.0-or-later
"""Chest-wall contact: the skin may not pass behind the chest (the plane
y = 0, docs/MODEL.md frame). A penalty on the deformed skin's penetration,

    E_chest = int_skin k_w/2 max(0, -(X_y + u_y))^2 dA,

k_w [Pa/m] per unit reference skin area: the pressure k_w d holds a skin
point d behind the wall. Frictionless (only the normal y acts). At the
inframammary fold the gravity-loaded lower pole otherwise swings a few mm
behind the chest in standing and reclined postures (docs/DIAGNOSE.md).
The energy is C1 (its Hessian jumps where contact starts).
"""
from common import Constant, X, domain, ds, param, u
from ufl import max_value

NAME = "chest_wall"
DEFAULT_ON = False
k_w = Constant(domain)

PARAMETERS = {
    "k_w": param("chest_wall.k", "Pa/m", 1.0e7, 0.0, 1e12,
                 "penalty stiffness of the chest wall against the skin (pressure per metre of "
                 "penetration behind y = 0)"),
}

penetration = max_value(0.0, -(X[1] + u[1]))
ENERGY = k_w / 2 * penetration ** 2 * ds("skin", "surface_quad")
