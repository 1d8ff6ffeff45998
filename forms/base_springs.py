# SPDX-License-Identifier: LGPL-3.0-or-later
"""Chassaignac (retromammary) space: a bed of springs on the base.

    E_base = int_base c(p)/2 |u|^2 dA,
    c(p) = c * (1 + (c_fold_ratio - 1) * max(0, -Z) / R_base)
The stiffness grows linearly from c at the base centre (Z >= 0) to
c * c_fold_ratio at the inframammary fold (Z = -R_base). c_fold_ratio = 1
gives a uniform bed; c -> infinity is the fixed base.
"""
from common import Constant, X, candidate, domain, dot, ds, fit_alias, u, param
from ufl import max_value

NAME = "base_springs"
c = Constant(domain)
c_fold_ratio = Constant(domain)
R_base = Constant(domain)

PARAMETERS = {
    "c": param("base.c", "Pa/m", 2.0e5, 0.0, 1e14, "spring stiffness of the Chassaignac space"),
    "c_fold_ratio": param("base.c_fold_ratio", "1", 1.0, 0.0, 1e4,
                          "stiffness at the inframammary fold relative to the centre", lo_open=True),
    "R_base": param("geometry.R", "m", 0.07, 0.0, 1.0, "base radius (bound from the geometry)", lo_open=True),
}
FIT = {"c": fit_alias("c", "stiffness")}
# q = 1/c, the compliance: q = 0 is the fixed base (the c -> infinity limit).
CANDIDATE = candidate("base.compliance", "m/Pa", 5e-6,
                      "the Chassaignac space: the base slides on springs (stiffness c = 1/compliance) "
                      "instead of being fixed to the chest",
                      sets={"c": "1/q"}, flags={"base.fixed": False})

c_of_p = c * (1 + (c_fold_ratio - 1) * max_value(0, -X[2]) / R_base)
ENERGY = c_of_p / 2 * dot(u, u) * ds("base", "surface_quad")
