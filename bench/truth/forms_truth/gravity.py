# SPDX-License-Identifier: LGPL-3.0-or-later
"""Mass forces in a posture (docs/MODEL.md "Postures"):

    E_gravity = - int_B rho * load * g_vec . u dV,
    g_vec = -g (cos(theta) e_z + sin(theta) e_y),
theta the chest angle (standing 0, supine 90 deg, all fours -90 deg); load in
[0, 1] the load factor of the ramp.
"""
import math

import numpy as np
import ufl
from dolfinx import fem


def gravity_vector(theta_deg, g=9.81):
    """g_vec = -g (cos theta e_z + sin theta e_y) in the body frame."""
    t = math.radians(theta_deg)
    return np.array([0.0, -g * math.sin(t), -g * math.cos(t)])


class Term:
    def __init__(self, ctx):
        self.rho = ctx.constant(970.0)
        self.load = ctx.constant(1.0)
        self.g_vec = fem.Constant(ctx.mesh, np.zeros(3))
        self.energy = -self.rho * self.load * ufl.dot(self.g_vec, ctx.u) * ctx.dx

    def set_posture(self, theta_deg, rho, g=9.81):
        if not (-180 <= theta_deg <= 180):
            raise ValueError(f"gravity: theta = {theta_deg} deg must lie in [-180, 180]")
        if not (rho > 0):
            raise ValueError(f"gravity: rho = {rho} kg/m^3 must be > 0")
        self.rho.value = rho
        self.g_vec.value = gravity_vector(theta_deg, g)
