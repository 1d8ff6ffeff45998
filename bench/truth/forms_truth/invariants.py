# SPDX-License-Identifier: LGPL-3.0-or-later
"""Isochoric invariants of the truth's kinematics (for the tissue laws
outside eq. (5): strain_stiffening.py, mooney_rivlin.py).

    C = F^T F,   J = det F,
    I1bar = J^(-2/3) tr C,
    I2bar = J^(-4/3) (tr(C)^2 - tr(C C)) / 2.

Both are 3 at F = I and at least 3 for any F (the principal stretches of
J^(-1/3) F have product 1); for a small strain eps both are
3 + 2 |dev eps|^2 + O(eps^3), so I1bar - 3 and I2bar - 3 vanish to second
order and a function of them beyond the linear term leaves the small-strain
moduli unchanged.
"""
import ufl


def isochoric_invariants(F, J):
    C = F.T * F
    I1 = ufl.tr(C)
    I2 = 0.5 * (I1 ** 2 - ufl.inner(C, C))     # tr(C C) = C : C (C symmetric)
    return J ** (-2.0 / 3.0) * I1, J ** (-4.0 / 3.0) * I2
