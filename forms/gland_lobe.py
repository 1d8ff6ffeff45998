# SPDX-License-Identifier: LGPL-3.0-or-later
"""Glandular lobe: the gland as a stiffer body buried under the fat, centred
on the nipple axis at height y_l above the chest wall,

    E_lobe = int_B m_l w(X) W(F) dV,   w(X) = max(1 - rho^2, 0)^2,
    rho^2 = (X^2 + Z^2) / a_l^2 + (Y - y_l)^2 / b_l^2,

with W the tissue's neo-Hookean density (eq. 5, same mu and lambda): at the
lobe's centre the tissue is (1 + m_l) times stiffer, and the excess falls
smoothly (C1) to nothing on the ellipsoid rho = 1, of radius a_l around the
axis and half-depth b_l along it. gland_core.py is the other form of the
gland: a sharp cylinder through the whole depth, skin to chest. m_l = 0
reproduces the model without a gland. Not in the diagnosis' default
library (`--candidates` names it): on the gland-form set it changed no
verdict (docs/DIAGNOSE.md).
"""
from common import Constant, X, candidate, domain, dx, F, J, neo_hooke, param
from tissue import mu, lmbda
from ufl import max_value

NAME = "gland_lobe"
DEFAULT_ON = False
m_l = Constant(domain)
y_l = Constant(domain)
a_l = Constant(domain)
b_l = Constant(domain)

PARAMETERS = {
    "m_l": param("gland.lobe_excess", "1", 2.0, 0.0, 1e4,
                 "extra stiffness at the glandular lobe's centre relative to the tissue "
                 "(centre = (1 + m_l) x tissue)"),
    "y_l": param("gland.lobe_height", "m", 0.02, 0.0, 1.0,
                 "height of the lobe's centre above the chest wall, on the nipple axis"),
    "a_l": param("gland.lobe_radius", "m", 0.035, 0.0, 1.0,
                 "radius of the lobe around the nipple axis", lo_open=True),
    "b_l": param("gland.lobe_half_depth", "m", 0.02, 0.0, 1.0,
                 "half-depth of the lobe along the nipple axis", lo_open=True),
}
CANDIDATE = candidate("gland.lobe_excess", "1", 2.0,
                      "a stiffer glandular lobe buried under the fat on the nipple axis "
                      "(stiffness up to (1 + m_l) x tissue at its centre)",
                      sets={"m_l": "q"}, family="gland_core", default=False)

rho2 = (X[0] ** 2 + X[2] ** 2) / a_l ** 2 + (X[1] - y_l) ** 2 / b_l ** 2
weight = max_value(1.0 - rho2, 0.0) ** 2                        # w = max(1 - rho^2, 0)^2
ENERGY = m_l * weight * neo_hooke(F, J, mu, lmbda, 3) * dx
