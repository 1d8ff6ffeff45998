# SPDX-License-Identifier: LGPL-3.0-or-later
"""A truth problem: the baseline physics plus a set of hidden effects on one
element degree, sharing the mesh and the unknown of that degree.

The UFL forms depend only on (degree, effect names, structural choices such
as the tether law); shapes and strengths are Constants, so one compiled
problem serves every recording with the same effects.
"""
from dolfinx import fem

from forms_truth import EFFECTS, chest_contact, gravity, tissue
from forms_truth.candidate_forms import CANDIDATE_FORMS, EXTENSIONS, OTHER_FORMS
from forms_truth.context import Context
from geometry import TAGS
from solver import TruthModel


# Terms by name: the hidden effects, and the candidates' forms (pseudo_true.py).
MODULES = {**EFFECTS, **{m.NAME: m for m in (*CANDIDATE_FORMS.values(), *OTHER_FORMS.values(),
                                              *EXTENSIONS.values())}}


class Problem:
    def __init__(self, ctx, effects, chest_wall_k=None):
        """effects: list of (effect NAME, pattern); chest_wall_k: the chest
        wall's penalty stiffness [Pa/m] (None: no chest wall)."""
        self.ctx = ctx
        self.tissue = tissue.Term(ctx)
        self.gravity = gravity.Term(ctx)
        self.effects = {}
        for name, pattern in effects:
            self.effects[name] = MODULES[name].Term(ctx, pattern, self.tissue)
        terms = list(self.effects.values())
        if chest_wall_k is not None:
            terms.append(chest_contact.Term(ctx, chest_wall_k))
        fixed_base = not any(MODULES[n].REPLACES_FIXED_BASE for n in self.effects)
        if not fixed_base and any(getattr(MODULES[n], "HOLDS_BASE_NORMAL", False) for n in self.effects):
            fixed_base = "normal"      # the base slides along the chest: u_y = 0 only
        self.model = TruthModel(ctx, self.tissue, self.gravity, terms, fixed_base)

    def configure(self, material, effects, strengths):
        """material: dict mu, lambda [Pa]; effects: list of (name, pattern);
        strengths: dict name -> strength."""
        self.tissue.set(material["mu"], material["lambda"])
        for name, pattern in effects:
            self.effects[name].set_pattern(pattern)
            self.effects[name].set_strength(strengths[name])

    def solve_postures(self, postures, rho, starts=None):
        """Displacement arrays, one per posture {name, theta_deg}."""
        out = []
        for i, p in enumerate(postures):
            start = None if starts is None else starts[i]
            out.append(self.model.solve_posture(p["theta_deg"], rho, start))
        return out


def problem_key(degree, effects):
    return (degree,) + tuple(sorted((n, MODULES[n].structure(p)) for n, p in effects))


class Problems:
    """One Context per degree on the shared mesh; problems built on demand and
    kept for the recordings that follow."""

    def __init__(self, mesh, facet_tags, R, H, chest_wall_k=None):
        self.ctx = {d: Context(mesh, facet_tags, TAGS, R, H, degree=d) for d in (1, 2)}
        self.chest_wall_k = chest_wall_k
        self._cache = {}
        self._p2 = fem.Function(self.ctx[2].V)

    def get(self, degree, effects):
        key = problem_key(degree, effects)
        if key not in self._cache:
            self._cache[key] = Problem(self.ctx[degree], effects, self.chest_wall_k)
        return self._cache[key]

    def all(self):
        """Every problem built so far."""
        return list(self._cache.values())

    def p1_to_p2(self, u1):
        """Interpolate a P1 displacement array into the P2 space."""
        self.ctx[1].u.x.array[:] = u1
        self._p2.interpolate(self.ctx[1].u)
        return self._p2.x.array.copy()
