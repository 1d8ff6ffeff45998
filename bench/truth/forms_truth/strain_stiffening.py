# SPDX-License-Identifier: LGPL-3.0-or-later
"""Hidden effect outside breastsim's candidate library: a tissue law that
stiffens with strain (eq. (5) is neo-Hookean: its stiffness in shear does
not grow with the strain).

The tissue becomes W'(F) = W_law(I1bar) + U(F), with the isochoric invariant
I1bar = J^(-2/3) tr C (invariants.py) and the volumetric part of the
baseline, U(F) = W(F) - mu/2 (I1bar - 3) (W eq. (5); U vanishes for
J = 1 deformations' deviatoric part: tr C = I1bar when J = 1). The effect is
the difference, with x = I1bar - 3 >= 0:

    E_stiff = int_B [W_law(x) - mu/2 x] dV,

three laws (pattern "law"), each with the series
W_law = mu/2 (x + k2 x^2 + O(x^3)), so that the small-strain shear modulus
stays mu and k2 is the nonlinearity of all three:

    yeoh     W_law = mu/2 (x + k2 x^2 + k2 c3 x^3)         (C2 = mu k2 / 2, C3 = c3 C2)
    gent     W_law = -mu Jm/2 ln(1 - x/Jm),  Jm = 1/(2 k2)  (limiting chain stretch: x < Jm)
    demiray  W_law = mu/(2 b) (exp(b x) - 1),  b = 2 k2     (Demiray / Fung exponential)

Pattern: the law (drawn uniformly) and, for yeoh, c3 = C3/C2 in [0, 1].

Strength: k2 [1], calibrated to the target peak shape change. The manifest's
derived values give each law's own parameter (C2, C3 [Pa]; Jm; b).

No breastsim candidate: family "tissue_law" (an invariant-based energy
beyond neo-Hooke). Closest candidate: none.
"""
import math

import ufl

from .invariants import isochoric_invariants

NAME = "strain_stiffening"
FAMILY = "tissue_law"
CANDIDATE = None
CLOSEST = None
STRENGTH = ("k2", "1", 0.2)
REPLACES_FIXED_BASE = False

LAWS = ("yeoh", "gent", "demiray")
RANGES = {"c3": (0.0, 1.0)}


def draw_pattern(rng, law=None):
    law = law if law is not None else LAWS[int(rng.integers(len(LAWS)))]
    p = {"law": law}
    structure(p)
    if law == "yeoh":
        p["c3"] = round(float(rng.uniform(*RANGES["c3"])), 3)
    return p


def structure(pattern):
    """The law selects the UFL form."""
    if pattern["law"] not in LAWS:
        raise ValueError(f"{NAME}: law '{pattern['law']}' (allowed: {LAWS})")
    return (pattern["law"],)


def law_density(law, x, mu, k2, c3):
    """W_law(x) - mu/2 x (UFL or float), x = I1bar - 3."""
    if law == "yeoh":
        return 0.5 * mu * k2 * (x ** 2 + c3 * x ** 3)
    if law == "gent":
        Jm = 1.0 / (2.0 * k2)
        return -0.5 * mu * Jm * _ln(1.0 - x / Jm) - 0.5 * mu * x
    b = 2.0 * k2
    return 0.5 * mu / b * (_exp(b * x) - 1.0) - 0.5 * mu * x


def _ln(a):
    return math.log(a) if isinstance(a, float) else ufl.ln(a)


def _exp(a):
    return math.exp(a) if isinstance(a, float) else ufl.exp(a)


class Term:
    def __init__(self, ctx, pattern, tissue):
        (self.law,) = structure(pattern)
        self.ctx = ctx
        self.mu = tissue.mu
        self.k2 = ctx.constant(STRENGTH[2])
        self.c3 = ctx.constant()
        I1bar, _ = isochoric_invariants(ctx.F, ctx.J)
        self.x = I1bar - 3.0
        self.density = law_density(self.law, self.x, self.mu, self.k2, self.c3)
        self.energy = self.density * ctx.dx
        self.set_pattern(pattern)

    def set_pattern(self, pattern):
        if structure(pattern) != (self.law,):
            raise ValueError(f"{NAME}: this term was built for law '{self.law}'")
        self.c3.value = pattern.get("c3", 0.0)

    def set_strength(self, k2):
        if not (k2 > 0 and math.isfinite(k2)):
            raise ValueError(f"{NAME}: k2 = {k2} must be > 0")
        self.k2.value = k2

    def describe(self, k2):
        mu = float(self.mu.value)
        out = {"law": self.law, "k2": k2, "mu_Pa": mu}
        if self.law == "yeoh":
            out.update({"C1_Pa": mu / 2, "C2_Pa": mu * k2 / 2, "C3_Pa": mu * k2 * float(self.c3.value) / 2})
        elif self.law == "gent":
            out["Jm"] = 1.0 / (2.0 * k2)
        else:
            out["b"] = 2.0 * k2
        return out

    def q_equivalent(self, k2):
        return None
