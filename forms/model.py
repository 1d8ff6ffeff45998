# SPDX-License-Identifier: LGPL-3.0-or-later
"""The registered energy terms of breastsim and their metadata (no forms).

    Pi(u) = sum_k on_k E_k(u),  residual = dPi/du [v],  jacobian = d residual/du [du]

Each term is compiled as its own ffcx module (forms/term_forms.py) and the
C++ side composes Pi from their kernels behind the runtime switches on_k.
This module collects what the C++ registry needs (forms/gen_registry.py):
the parameters with their case keys, the default switches, the partner
fields, the diagnosis candidates and the --fit names, and refuses a Constant
name used by two terms (the C++ side binds Constants by name).
"""
import importlib

from ufl import Constant as _Constant
from ufl import Coefficient as _Coefficient
from ufl.algorithms import extract_coefficients as _extract_coefficients

from common import domain, GEOMETRY_FIT, TAGS  # noqa: F401
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


# Diagnosis candidates (calibrate/diagnose/candidates.hpp): a term may declare
# CANDIDATE = candidate(...) (common.py). Collected with the case keys its q sets.
CANDIDATES = {}
_RULES = ("q", "1/q", "keep_ratio")


def _keyed_scalar(m, name, what):
    """The case key of the scalar parameter `name` of term module m."""
    p = m.PARAMETERS.get(name)
    if p is None or not p["key"] or p["shape"]:
        raise RuntimeError(f"term '{m.NAME}': {what} '{name}' is not a scalar parameter of the term "
                           "with a case key")
    return p["key"]


for _m in _modules:
    _c = getattr(_m, "CANDIDATE", None)
    if _c is None:
        continue
    _where = f"term '{_m.NAME}': CANDIDATE"
    if not (isinstance(_c.get("typical"), (int, float)) and _c["typical"] > 0):
        raise RuntimeError(f"{_where}: typical = {_c.get('typical')!r} must be a number > 0")
    for _name in ("parameter", "unit", "physics"):
        if not isinstance(_c.get(_name), str) or (_name != "unit" and not _c[_name]):
            raise RuntimeError(f"{_where}: {_name} must be a non-empty string")
    if not _c["sets"]:
        raise RuntimeError(f"{_where}: sets is empty (which parameter does q set?)")
    _sets = []
    for _i, (_name, _rule) in enumerate(_c["sets"].items()):
        if _rule not in _RULES or (_i == 0 and _rule == "keep_ratio"):
            raise RuntimeError(f"{_where}: rule '{_rule}' of '{_name}' is not allowed (allowed: "
                               "'q', '1/q'; after the first also 'keep_ratio')")
        _sets.append((_keyed_scalar(_m, _name, "CANDIDATE sets"), _rule))
    for _key, _value in _c["flags"].items():
        if not isinstance(_key, str) or not isinstance(_value, bool):
            raise RuntimeError(f"{_where}: flags must map case keys to True/False, got {_key!r}: {_value!r}")
    if not isinstance(_c.get("default", True), bool):
        raise RuntimeError(f"{_where}: default = {_c['default']!r} must be True or False")
    if _c.get("family") and _c.get("extends"):
        raise RuntimeError(f"{_where}: family and extends exclude each other (an extension names "
                           "the physics of the candidate it extends)")
    CANDIDATES[_m.NAME] = dict(parameter=_c["parameter"], unit=_c["unit"], typical=float(_c["typical"]),
                               physics=_c["physics"], sets=_sets, flags=list(_c["flags"].items()),
                               family=_c.get("family") or _m.NAME, extends=_c.get("extends") or "",
                               default=_c.get("default", True))
for _n, _c in CANDIDATES.items():
    _base = CANDIDATES.get(_c["extends"]) if _c["extends"] else None
    if _c["extends"] and (_base is None or _base["extends"]):
        raise RuntimeError(f"term '{_n}': CANDIDATE extends '{_c['extends']}', which must be the "
                           "name of a candidate that extends none")
    if _base is not None:
        _c["family"] = _base["family"]
for _n, _c in CANDIDATES.items():
    if _c["family"] not in CANDIDATES or CANDIDATES[_c["family"]]["family"] != _c["family"]:
        raise RuntimeError(f"term '{_n}': CANDIDATE family '{_c['family']}' must be the name of a "
                           "candidate that is its own family")

# --fit names (calibrate/fit/fit_parameters.hpp): a term's FIT = {name: fit_alias(...)}
# names its parameters, common.GEOMETRY_FIT the neutral shape. Each name and each
# case key once.
FIT_ALIASES = {}
_ROLES = ("stiffness", "density", "shape")


def _add_alias(alias, key, role, term):
    if alias in FIT_ALIASES:
        raise RuntimeError(f"--fit name '{alias}' declared twice (terms '{FIT_ALIASES[alias]['term']}' "
                           f"and '{term}')")
    if any(a["key"] == key for a in FIT_ALIASES.values()):
        raise RuntimeError(f"case key '{key}' has two --fit names")
    if role not in _ROLES:
        raise RuntimeError(f"--fit name '{alias}': role '{role}' is not one of {', '.join(_ROLES)}")
    FIT_ALIASES[alias] = dict(key=key, role=role, term=term)


for _m in _modules:
    for _alias, _f in getattr(_m, "FIT", {}).items():
        _add_alias(_alias, _keyed_scalar(_m, _f["target"], f"FIT '{_alias}'"), _f["role"], _m.NAME)
for _alias, _f in GEOMETRY_FIT.items():
    _add_alias(_alias, _f["target"], _f["role"], "")
