# SPDX-License-Identifier: LGPL-3.0-or-later
"""Tissue law features beyond eq. (5): invariant-based energy densities
added to the tissue's neo-Hookean one,

    E = int_B sum_k b_k f_k(F) dV,
    f_1 = (I1b - 3)^2,  f_2 = (I1b - 3)^3   (Yeoh: stiffening with stretch),
    f_3 = I2b - 3                            (Mooney-Rivlin: the second invariant),
    I1b = J^(-2/3) tr C,  I2b = J^(-4/3) (tr(C)^2 - tr(C^2)) / 2,  C = F^T F,

b = 0 the law of eq. (5) alone. The diagnosis selects and fits the
features when no candidate explains the residual (docs/DISCOVERY.md,
"Law discovery") and writes what it found as a term file of this form.
The defaults are an example: b_1 = 100 Pa, a mildly stiffening tissue.
"""
from common import Constant, F, J, domain, dx, param, tr

NAME = "tissue_law"
DEFAULT_ON = False
b_law = Constant(domain, shape=(3,))

PARAMETERS = {
    "b_law": param("tissue_law.coefficients", "Pa", [100.0, 0.0, 0.0], -1e8, 1e8,
                   "coefficients b_k of the features (I1b - 3)^2, (I1b - 3)^3, I2b - 3", shape=(3,)),
}

C = F.T * F
I1b = J ** (-2.0 / 3.0) * tr(C)                              # isochoric first invariant
I2b = J ** (-4.0 / 3.0) * (tr(C) ** 2 - tr(C * C)) / 2      # isochoric second invariant
FEATURES = [(I1b - 3) ** 2, (I1b - 3) ** 3, I2b - 3]
ENERGY = sum(b_law[k] * f for k, f in enumerate(FEATURES)) * dx
