# SPDX-License-Identifier: LGPL-3.0-or-later
"""Throw-away term of the edit-loop benchmark (bench/edit_loop.sh): a dead
pressure p on the skin, pushing along the reference outward normal N,

    E_skin_pressure = - int_skin p N . u dA.
"""
from common import Constant, N, domain, dot, ds, u, param

NAME = "skin_pressure"
DEFAULT_ON = False
p_skin = Constant(domain)

PARAMETERS = {
    "p_skin": param("skin_pressure.p", "Pa", 0.0, -1e5, 1e5, "dead pressure on the skin (outward > 0)"),
}

ENERGY = -p_skin * dot(N, u) * ds("skin", "surface")
