"""Total energy of breastsim: the registered terms, each behind a runtime
on/off switch Constant on_<term>, and the forms derived from it.

    Pi(u) = sum_k on_k E_k(u),  residual = dPi/du [v],  jacobian = d residual/du [du]

Every Constant of every term is hoisted into this module's namespace so that
ffcx names it after its variable (the C++ side binds parameters by name).
"""
import importlib

from ufl import Constant as _Constant
from ufl import Coefficient as _Coefficient
from ufl import derivative as _derivative
from ufl.algorithms import extract_coefficients as _extract_coefficients

from common import domain, u, v, du, J, dx, DEGREE, TAGS, QDEG  # noqa: F401
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

energy = sum(globals()["on_" + _m.NAME] * _m.ENERGY for _m in _modules)
residual = _derivative(energy, u, v)
jacobian = _derivative(residual, u, du)

# Observables and checks.
volume = J * dx                       # deformed volume of the model (half breast)

forms = [energy, residual, jacobian, volume]

# Reference area of each tagged boundary part (tests, reports).
from common import X as _X, ds as _ds  # noqa: E402
for _tag in TAGS:
    globals()["area_" + _tag] = (1 + 0 * _X[0]) * _ds(_tag)
    forms.append(globals()["area_" + _tag])
# Each term on its own, without its switch (tests, reports, diagnosis).
for _m in _modules:
    _name, _E = _m.NAME, _m.ENERGY
    globals()["energy_" + _name] = _E
    globals()["residual_" + _name] = _derivative(_E, u, v)
    globals()["jacobian_" + _name] = _derivative(globals()["residual_" + _name], u, du)
    forms += [globals()["energy_" + _name], globals()["residual_" + _name],
              globals()["jacobian_" + _name]]

# Partner fields (see forms/tissue_suture.py): a term may declare
# PARTNER = dict(coefficient=..., face_a=..., face_b=..., map_matrix=..., map_shift=...):
# its Coefficient w (in the space of u) is set by the C++ side to w = P u, the
# values of u at the images g(X) = G X + t of the nodes of face_a. The term's
# partial derivatives in w are compiled here; C++ applies the chain rule
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
    _Ew = _derivative(_m.ENERGY, _w, v)
    globals()["partner_residual_" + _m.NAME] = _Ew
    globals()["partner_jacobian_uw_" + _m.NAME] = _derivative(_derivative(_m.ENERGY, u, v), _w, du)
    globals()["partner_jacobian_ww_" + _m.NAME] = _derivative(_Ew, _w, du)
    forms += [globals()["partner_" + _k + "_" + _m.NAME] for _k in ("residual", "jacobian_uw", "jacobian_ww")]

# det F at the reference-cell nodes of the element (vertices and, for P2,
# edge midpoints): used to refuse inverted elements.
_points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
if DEGREE == 2:
    _points += [[0, .5, .5], [.5, 0, .5], [.5, .5, 0], [0, 0, .5], [0, .5, 0], [.5, 0, 0]]
_points.append([0.25, 0.25, 0.25])
detF = J
expressions = [(detF, _points)]
