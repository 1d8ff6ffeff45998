# SPDX-License-Identifier: LGPL-3.0-or-later
"""Mass forces: the potential of gravity in the body frame.

    E_gravity = - int_B rho * load * g_vec . u dV
g_vec is set by the posture (docs/MODEL.md: g_vec = -g (cos(theta) e_z + sin(theta) e_y));
load in [0, 1] is the load factor driven by the load stepping.
"""
from common import Constant, domain, dot, dx_load, u, fit_alias, param

NAME = "gravity"
rho = Constant(domain)
g_vec = Constant(domain, shape=(3,))
load = Constant(domain)

PARAMETERS = {
    "rho": param("tissue.rho", "kg/m^3", 970.0, 0.0, 1e5, "tissue mass density"),
    "g_vec": param("", "m/s^2", [0.0, 0.0, -9.81], -1e3, 1e3,
                   "gravity vector in the body frame (set by the posture)", shape=(3,)),
    "load": param("", "1", 1.0, 0.0, 1.0, "load factor (set by load stepping)"),
}
FIT = {"rho": fit_alias("rho", "density")}

ENERGY = -rho * load * dot(g_vec, u) * dx_load
