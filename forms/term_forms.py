# SPDX-License-Identifier: LGPL-3.0-or-later
"""One energy term as its own ffcx module (term_<name>_p<degree>).

The term is forms/<BREASTSIM_TERM>.py. Its forms:
    energy_<name>   = E(u)
    residual_<name> = dE/du [v]
    jacobian_<name> = d residual/du [du]
and, for a term with a PARTNER field w (forms/model.py), the partial
derivatives E_w, E_uw, E_ww (partner_residual_/partner_jacobian_uw_/
partner_jacobian_ww_<name>).

The C++ side composes the total energy Pi = sum_k on_k E_k from these
kernels (src/model/composite_form.hpp), so an edit of one term recompiles
only that term's module. Every Constant and Coefficient the term module sees
is hoisted into this namespace: ffcx names them after their variables, and
the C++ side binds them by name.
"""
import importlib
import os

from ufl import Constant as _Constant
from ufl import Coefficient as _Coefficient
from ufl import derivative as _derivative

from common import u, v, du  # noqa: F401

_name = os.environ["BREASTSIM_TERM"]
_m = importlib.import_module(_name)
if getattr(_m, "NAME", None) != _name:
    raise RuntimeError(f"forms/{_name}.py must set NAME = '{_name}'")

for _k, _obj in vars(_m).items():
    if isinstance(_obj, (_Constant, _Coefficient)) and not _k.startswith("_"):
        globals()[_k] = _obj

_E = _m.ENERGY
globals()["energy_" + _name] = _E
globals()["residual_" + _name] = _derivative(_E, u, v)
globals()["jacobian_" + _name] = _derivative(globals()["residual_" + _name], u, du)
forms = [globals()[k + "_" + _name] for k in ("energy", "residual", "jacobian")]

_partner = getattr(_m, "PARTNER", None)
if _partner is not None:
    _w = getattr(_m, _partner["coefficient"])
    _Ew = _derivative(_E, _w, v)
    globals()["partner_residual_" + _name] = _Ew
    globals()["partner_jacobian_uw_" + _name] = _derivative(_derivative(_E, u, v), _w, du)
    globals()["partner_jacobian_ww_" + _name] = _derivative(_Ew, _w, du)
    forms += [globals()["partner_" + k + "_" + _name]
              for k in ("residual", "jacobian_uw", "jacobian_ww")]
