"""The registered energy terms of breastsim and their metadata (no forms).

    Pi(u) = sum_k on_k E_k(u),  residual = dPi/du [v],  jacobian = d residual/du [du]

Each term is compiled as its own ffcx module (forms/term_forms.py) and the
C++ side composes Pi from their kernels behind the runtime switches on_k.
This module collects what the C++ registry needs (forms/gen_registry.py):
the parameters with their case keys, the default switches and the partner
fields, and refuses a Constant name used by two terms (the C++ side binds
Constants by name).
"""
import importlib

from ufl import Constant as _Constant
from ufl import Coefficient as _Coefficient
from ufl.algorithms import extract_coefficients as _extract_coefficients

from common import domain, TAGS  # noqa: F401
from registry import TERMS

_modules = [importlib.import_module(name) for name in TERMS]
PARAMETERS = {}
SWITCHES = {}

for _m in _modules:
    for _name, _obj in vars(_m).items():
        if isinstance(_obj, (_Constant, _Coefficient)) and not _name.startswith("_"):
            if _name in globals() and globals()[_name] is not _obj:
                raise RuntimeError(f"UFL name clash: '{_name}' defined by term '{_m.NAME}' "
                                   "and another module")
            globals()[_name] = _obj
    for _name in _m.PARAMETERS:
        if not isinstance(getattr(_m, _name, None), _Constant):
            raise RuntimeError(f"term '{_m.NAME}': parameter '{_name}' is not a module-level Constant")
        PARAMETERS[_name] = dict(_m.PARAMETERS[_name], term=_m.NAME)
    globals()["on_" + _m.NAME] = _Constant(domain)
    SWITCHES[_m.NAME] = getattr(_m, "DEFAULT_ON", True)

# Partner fields (see forms/tissue_suture.py): a term may declare
# PARTNER = dict(coefficient=..., face_a=..., face_b=..., map_matrix=..., map_shift=...):
# its Coefficient w (in the space of u) is set by the C++ side to w = P u, the
# values of u at the images g(X) = G X + t of the nodes of face_a. The term's
# partial derivatives in w are compiled with it (term_forms.py); C++ applies the chain rule
#   dE/du = E_u + P^T E_w,  d2E/du2 = E_uu + E_uw P + P^T E_wu + P^T E_ww P.
# A partner Coefficient belongs to its term alone (so the total's w-derivative
# is on_term times the term's, and no cross terms between partners arise).
PARTNERS = {}
for _m in _modules:
    _p = getattr(_m, "PARTNER", None)
    if _p is None:
        continue
    _w = getattr(_m, _p["coefficient"], None)
    if not isinstance(_w, _Coefficient):
        raise RuntimeError(f"term '{_m.NAME}': PARTNER coefficient '{_p['coefficient']}' "
                           "is not a module-level Coefficient")
    for _name in ("face_a", "face_b"):
        if _p[_name] not in TAGS:
            raise RuntimeError(f"term '{_m.NAME}': PARTNER {_name} '{_p[_name]}' is not a tag")
    for _name in ("map_matrix", "map_shift"):
        if _p[_name] not in _m.PARAMETERS:
            raise RuntimeError(f"term '{_m.NAME}': PARTNER {_name} '{_p[_name]}' is not a parameter")
    for _o in _modules:
        if _o is not _m and _w in _extract_coefficients(_o.ENERGY):
            raise RuntimeError(f"partner coefficient '{_p['coefficient']}' of term '{_m.NAME}' "
                               f"is also used by term '{_o.NAME}'")
    PARTNERS[_m.NAME] = dict(_p)

