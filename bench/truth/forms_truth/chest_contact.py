# SPDX-License-Identifier: LGPL-3.0-or-later
"""Baseline term of the truth (not a hidden effect): the chest wall.

The skin may not pass behind the chest, the plane y = 0. A penalty on the
deformed skin's penetration depth d = max(0, -(X_y + u_y)):

    E_wall = int_skin k/2 d^2 dA,

k [Pa/m] per unit reference skin area (pressure k d at depth d). Without
it the gravity-loaded lower pole swings 2-3 mm behind the chest at the
inframammary fold in standing and reclined postures.
"""
import ufl

NAME = "chest_contact"


class Term:
    def __init__(self, ctx, k):
        if not k > 0:
            raise ValueError(f"{NAME}: k = {k} Pa/m must be > 0")
        self.k = ctx.constant(k)
        depth = ufl.max_value(0.0, -(ctx.X[1] + ctx.u[1]))
        self.energy = 0.5 * self.k * depth ** 2 * ctx.ds("skin")
