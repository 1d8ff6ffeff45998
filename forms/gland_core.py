# SPDX-License-Identifier: LGPL-3.0-or-later
"""Glandular core: a stiffer region of tissue around the nipple axis,

    E_gland = int_B m_g chi(X) W(F) dV,   chi(X) = 1 where X^2 + Z^2 < r_g^2, else 0,

with W the tissue's neo-Hookean density (eq. 5, same mu and lambda): inside
the core the tissue is (1 + m_g) times stiffer. m_g = 0 reproduces the model
without a core.
"""
from common import Constant, X, candidate, domain, dx, F, J, neo_hooke, param
from tissue import mu, lmbda
from ufl import conditional, lt

NAME = "gland_core"
DEFAULT_ON = False
m_g = Constant(domain)
r_g = Constant(domain)

PARAMETERS = {
    "m_g": param("gland.excess", "1", 2.0, 0.0, 1e4,
                 "extra stiffness of the glandular core relative to the tissue (core = (1 + m_g) x tissue)"),
    "r_g": param("gland.radius", "m", 0.03, 0.0, 1.0,
                 "radius of the glandular core around the nipple axis", lo_open=True),
}
CANDIDATE = candidate("gland.excess", "1", 2.0,
                      "a stiffer glandular core around the nipple axis (stiffness (1 + m_g) x tissue)",
                      sets={"m_g": "q"})

core = conditional(lt(X[0] ** 2 + X[2] ** 2, r_g ** 2), 1.0, 0.0)
ENERGY = m_g * core * neo_hooke(F, J, mu, lmbda, 3) * dx
