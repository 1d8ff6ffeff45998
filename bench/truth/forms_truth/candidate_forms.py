"""The forms of breastsim's candidate terms, written in the truth code from
their documented equations (docs/DIAGNOSE.md, SPEC.md; nothing is imported
from forms/), for one purpose: the pseudo-true value of a candidate, the
value whose solve on the truth's own mesh reproduces a hidden effect best
(pseudo_true.py). They never make a recording.

    base_springs:         E = int_base c/2 |u|^2 dA,  c = 1/q uniform
                          (replaces the fixed base)
    gland_core:           E = int_B q chi(X) W(F) dV,  chi = 1 where
                          X^2 + Z^2 < r_g^2 (r_g = 30 mm), W eq. (5)
    suspensory_ligament:  E = int_skin q/2 w(X) |u|^2 dA,  w = 1 where Z > 0

The skin candidate (a neo-Hookean tension-field membrane) is a different
constitutive law from the truth's fibre net and has no form here.
"""
import math

import ufl

R_G = 0.03  # m, gland.radius of cases/default.toml


class _Form:
    """Module-like interface of forms_truth effects (problem.Problem)."""
    REPLACES_FIXED_BASE = False

    @staticmethod
    def structure(pattern):
        return ()

    def __init__(self, ctx, q_name):
        self.ctx, self.q_name = ctx, q_name
        self.q = ctx.constant()

    def set_pattern(self, pattern):
        pass

    def set_strength(self, q):
        if not (q > 0 and math.isfinite(q)):
            raise ValueError(f"candidate form {self.NAME}: {self.q_name} = {q} must be > 0")
        self.q.value = self.value_of(q)

    @staticmethod
    def value_of(q):
        return q


class UniformBed(_Form):
    NAME = "candidate:base_springs"
    CANDIDATE = "base_springs"
    REPLACES_FIXED_BASE = True

    def __init__(self, ctx, pattern=None, tissue=None):
        super().__init__(ctx, "base.compliance")
        self.energy = 0.5 * self.q * ufl.dot(ctx.u, ctx.u) * ctx.ds("base")   # c/2 |u|^2

    @staticmethod
    def value_of(compliance):
        return 1.0 / compliance                                              # c = 1/q


class SharpCore(_Form):
    NAME = "candidate:gland_core"
    CANDIDATE = "gland_core"

    def __init__(self, ctx, pattern=None, tissue=None):
        super().__init__(ctx, "gland.excess")
        X = ctx.X
        chi = ufl.conditional(ufl.lt(X[0] ** 2 + X[2] ** 2, R_G ** 2), 1.0, 0.0)
        self.energy = self.q * chi * tissue.density * ctx.dx                 # q chi W(F)


class UpperPoleSprings(_Form):
    NAME = "candidate:suspensory_ligament"
    CANDIDATE = "suspensory_ligament"

    def __init__(self, ctx, pattern=None, tissue=None):
        super().__init__(ctx, "ligament.k")
        w = ufl.conditional(ufl.gt(ctx.X[2], 0.0), 1.0, 0.0)
        self.energy = 0.5 * self.q * w * ufl.dot(ctx.u, ctx.u) * ctx.ds("skin")  # q/2 w |u|^2


def _module(cls):
    """The class itself serves as the module: NAME, CANDIDATE, structure,
    REPLACES_FIXED_BASE and Term."""
    cls.Term = cls
    return cls


CANDIDATE_FORMS = {c.CANDIDATE: _module(c) for c in (UniformBed, SharpCore, UpperPoleSprings)}
