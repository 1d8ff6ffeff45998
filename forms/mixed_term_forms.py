# SPDX-License-Identifier: LGPL-3.0-or-later
"""One energy term on the mixed (u, p) space as its own ffcx module
(mixed_<name>_p<degree>, forms/mixed_forms_common.py):
    energy_<name>   = E(w)
    residual_<name> = dE/dw [q]
    jacobian_<name> = d residual/dw [dw]
The C++ side composes them like the displacement terms (term_forms.py).
"""
import importlib
import os

from ufl import Constant as _Constant
from ufl import derivative as _derivative

from mixed_forms_common import w, q, dw, mixed_energy, has_mixed_form  # noqa: F401

_name = os.environ["BREASTSIM_TERM"]
_m = importlib.import_module(_name)
if not has_mixed_form(_m):
    raise RuntimeError(f"term '{_name}' has no mixed form (it has a partner field)")

for _k, _obj in vars(_m).items():
    if isinstance(_obj, _Constant) and not _k.startswith("_"):
        globals()[_k] = _obj

_E = mixed_energy(_m)
globals()["energy_" + _name] = _E
globals()["residual_" + _name] = _derivative(_E, w, q)
globals()["jacobian_" + _name] = _derivative(globals()["residual_" + _name], w, dw)
forms = [globals()[k + "_" + _name] for k in ("energy", "residual", "jacobian")]
