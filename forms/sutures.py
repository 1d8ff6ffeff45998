# SPDX-License-Identifier: LGPL-3.0-or-later
"""Sutures (knitting conditions, paper eq. (3)-(4)) as a penalty energy.

suture_abd (the cut face on plane P1) is sewn to the symmetry plane x = 0
(it meets its mirror image); suture_bcd (on P2) is sewn to the chest y = 0.
Points slide freely within the target plane: only the signed distance of the
deformed face to its plane is penalised. The closure is driven like a load:
with closure s in [0, 1] the faces are pulled to the fraction (1 - s) of
their initial distance,
    E = k/2 int_abd (X_x + u_x - (1 - s) X_x)^2 dA + k/2 int_bcd (X_y + u_y - (1 - s) X_y)^2 dA,
so at s = 1 the remaining gap is |X_x + u_x| (resp. |X_y + u_y|) = O(traction / k);
k is raised until the largest gap is below the requested tolerance.
"""
from common import Constant, X, domain, ds, u, param

NAME = "sutures"
DEFAULT_ON = False
k_suture = Constant(domain)
closure = Constant(domain)

PARAMETERS = {
    "k_suture": param("surgery.k_suture", "Pa/m", 1.0e7, 0.0, 1e14,
                      "initial suture penalty stiffness (raised until the gap is closed)", lo_open=True),
    "closure": param("", "1", 1.0, 0.0, 1.0, "suture closure fraction (set by the closure stepping)"),
}

gap_abd = u[0] + closure * X[0]
gap_bcd = u[1] + closure * X[1]
ENERGY = (k_suture / 2 * gap_abd ** 2 * ds("suture_abd", "surface_quad")
          + k_suture / 2 * gap_bcd ** 2 * ds("suture_bcd", "surface_quad"))
