# SPDX-License-Identifier: LGPL-3.0-or-later
"""Hidden effect outside breastsim's candidate library: a second-invariant
(Mooney-Rivlin) term in the tissue law.

The tissue becomes W'(F) = C10 (I1bar - 3) + C01 (I2bar - 3) + U(F), with
the isochoric invariants I1bar, I2bar (invariants.py), the volumetric part
of the baseline U(F) = W(F) - mu/2 (I1bar - 3) (W eq. (5)) and

    C01 = f mu / 2,   C10 = (1 - f) mu / 2,   f = r / (1 + r),   r = C01 / C10,

so that the small-strain shear modulus 2 (C10 + C01) stays mu and the
effect is the law's form, not a change of mu: a share f of the shear
stiffness moves from the first to the second invariant. The effect is the
difference,

    E_MR = int_B C01 [(I2bar - 3) - (I1bar - 3)] dV = int_B f mu/2 (I2bar - I1bar) dV,

which is of third order in the strain (invariants.py) and odd in the
stretch (uniaxial stretch l: I1bar = l^2 + 2/l,
I2bar = 2 l + 1/l^2, I2bar - I1bar = -2 (l - 1)^3 + O((l - 1)^4)): the
tissue gets softer in extension and stiffer in compression than neo-Hooke.

Pattern: none (the term has no shape); draw_pattern returns {}.

Strength: r = C01 / C10 in (0, inf) [1], calibrated to the target peak
shape change; the share f = 2 C01 / mu = r / (1 + r) stays below 1 (C10 > 0:
the law stays strongly elliptic), so the effect saturates at the I2-only law
(f -> 1): a stiff, nearly incompressible truth may not reach a 3 mm target
(the manifest's peak_change_mm says what it reached).

No breastsim candidate: family "tissue_law". Closest candidate: none.
"""
import math

from .invariants import isochoric_invariants

NAME = "mooney_rivlin"
FAMILY = "tissue_law"
CANDIDATE = None
CLOSEST = None
STRENGTH = ("c01_over_c10", "1", 1.0)
REPLACES_FIXED_BASE = False

RANGES = {}


def draw_pattern(rng):
    return {}


def structure(pattern):
    return ()


def share(r):
    """f = r / (1 + r): the share of the shear modulus on I2bar."""
    return r / (1.0 + r)


class Term:
    def __init__(self, ctx, pattern, tissue):
        self.ctx = ctx
        self.mu = tissue.mu
        self.f = ctx.constant()
        I1bar, I2bar = isochoric_invariants(ctx.F, ctx.J)
        self.density = 0.5 * self.f * self.mu * (I2bar - I1bar)       # C01 ((I2bar - 3) - (I1bar - 3))
        self.energy = self.density * ctx.dx
        self.set_pattern(pattern)

    def set_pattern(self, pattern):
        pass

    def set_strength(self, r):
        if not (r > 0 and math.isfinite(r)):
            raise ValueError(f"{NAME}: r = C01/C10 = {r} must be > 0")
        self.f.value = share(r)

    def describe(self, r):
        mu, f = float(self.mu.value), share(r)
        return {"c01_over_c10": r, "f": f, "C10_Pa": (1.0 - f) * mu / 2, "C01_Pa": f * mu / 2, "mu_Pa": mu}

    def q_equivalent(self, r):
        return None
