# SPDX-License-Identifier: LGPL-3.0-or-later
"""The term-free forms of the mixed formulation (module mixed_geometry_p<degree>):

    pressure_integral = int_B p dV     (mean pressure = this / reference_volume)
    reference_volume  = int_B 1 dV

It also provides the mixed space ('w') for the C++ side.
"""
from common import X, dx
from mixed_forms_common import w, p  # noqa: F401

pressure_integral = p * dx
reference_volume = (1 + 0 * X[0]) * dx
forms = [pressure_integral, reference_volume]
