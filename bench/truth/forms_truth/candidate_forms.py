# SPDX-License-Identifier: LGPL-3.0-or-later
"""The forms of breastsim's candidate terms, written in the truth code from
their documented equations (docs/DIAGNOSE.md, docs/MODEL.md, the docstring of
forms/skin.py; nothing is imported from forms/), for one purpose: the
pseudo-true value of a candidate, the value whose solve on the truth's own
mesh reproduces a hidden effect best (pseudo_true.py). They never make a
recording.

    base_springs:         E = int_base c/2 |u|^2 dA,  c = 1/q uniform
                          (replaces the fixed base)
    gland_core:           E = int_B q chi(X) W(F) dV,  chi = 1 where
                          X^2 + Z^2 < r_g^2 (r_g = 30 mm), W eq. (5)
    gland_lobe:           E = int_B q w(X) W(F) dV,  w = max(1 - rho^2, 0)^2,
                          rho^2 = (X^2 + Z^2)/a_l^2 + (Y - y_l)^2/b_l^2
                          (y_l = 20, a_l = 35, b_l = 20 mm; the same physics
                          as a lobe buried on the nipple axis)
    suspensory_ligament:  E = int_skin q/2 w(X) |u|^2 dA,  w = 1 where Z > 0
    suspensory_cables:    E = int_skin q/2 w(X) max(|x - A| - |X - A|, 0)^2 dA,
                          A = (X_x, 0, X_z + d_a), d_a = 20 mm, x = X + u
                          (the same physics as tension-only cables)
    skin:                 E = int_skin t_s W_s dA,  the relaxed tension-field
                          neo-Hookean membrane of forms/skin.py, mu_s = q,
                          lambda_s = q (keep_ratio, default ratio 1),
                          t_s = 1.5 mm
    skin_upper_pole:      E = int_skin [Z > 0] t_s W_s dA,  mu_u = lambda_u = q
                          (a regional variation that extends skin: the
                          form skin+skin_upper_pole is the two together,
                          the upper pole carrying both terms' energies)
"""
import math

import ufl

R_G = 0.03  # m, gland.radius of cases/default.toml
D_A = 0.02  # m, cables.anchor_rise of cases/default.toml
T_S = 0.0015  # m, skin.thickness of cases/default.toml
LOBE = (0.02, 0.035, 0.02)  # m, gland.lobe_height, gland.lobe_radius, gland.lobe_half_depth
DISC_MIN = 1e-10  # (l1^2 - l2^2)^2 below this: the plain law (forms/skin.py)


def upper_pole(X):
    """[Z > 0], the region of the upper-pole forms."""
    return ufl.conditional(ufl.gt(X[2], 0.0), 1.0, 0.0)


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


class BuriedLobe(_Form):
    NAME = "candidate:gland_lobe"
    CANDIDATE = "gland_lobe"
    PHYSICS = "gland_core"
    PARAMETER = "gland.lobe_excess"

    def __init__(self, ctx, pattern=None, tissue=None):
        super().__init__(ctx, self.PARAMETER)
        X = ctx.X
        y_l, a_l, b_l = LOBE
        rho2 = (X[0] ** 2 + X[2] ** 2) / a_l ** 2 + (X[1] - y_l) ** 2 / b_l ** 2
        w = ufl.max_value(1.0 - rho2, 0.0) ** 2
        self.energy = self.q * w * tissue.density * ctx.dx                   # q w W(F)


class UpperPoleSprings(_Form):
    NAME = "candidate:suspensory_ligament"
    CANDIDATE = "suspensory_ligament"

    def __init__(self, ctx, pattern=None, tissue=None):
        super().__init__(ctx, "ligament.k")
        w = upper_pole(ctx.X)
        self.energy = 0.5 * self.q * w * ufl.dot(ctx.u, ctx.u) * ctx.ds("skin")  # q/2 w |u|^2


class UpperPoleCables(_Form):
    NAME = "candidate:suspensory_cables"
    CANDIDATE = "suspensory_cables"
    PHYSICS = "suspensory_ligament"
    PARAMETER = "cables.k"

    def __init__(self, ctx, pattern=None, tissue=None):
        super().__init__(ctx, self.PARAMETER)
        X, u = ctx.X, ctx.u
        w = upper_pole(X)
        A = ufl.as_vector((X[0], 0.0, X[2] + D_A))
        stretch = ufl.max_value(ufl.sqrt(ufl.dot(X + u - A, X + u - A)) - ufl.sqrt(ufl.dot(X - A, X - A)), 0.0)
        self.energy = 0.5 * self.q * w * stretch ** 2 * ctx.ds("skin")     # q/2 w <|x-A| - |X-A|>^2


def membrane_density(mu, lmbda, l1, l2):
    """W_s(l1, l2) = mu/2 (l1^2 + l2^2 - 2 - 2 ln(l1 l2)) + lambda/2 (l1 l2 - 1)^2."""
    return mu / 2 * (l1 ** 2 + l2 ** 2 - 2 - 2 * ufl.ln(l1 * l2)) + lmbda / 2 * (l1 * l2 - 1) ** 2


def tension_field_density(ctx, mu, lmbda):
    """The relaxed membrane energy per unit volume of skin (forms/skin.py):
    C_s = P F^T F P (P = I - N (x) N), J_s = |J F^-T N|, I1 = tr C_s,
    l1^2 = (I1 + sqrt(I1^2 - 4 J_s^2)) / 2, l2 = J_s / l1;
    taut (l2 >= n(l1)): W_s; wrinkled (l1 > 1, l2 < n): W_s(l1, n(l1));
    slack (l1 <= 1): 0; the plain W_s where I1^2 - 4 J_s^2 < DISC_MIN."""
    F, N = ctx.F, ctx.N
    P = ctx.I - ufl.outer(N, N)
    C_s = P * F.T * F * P
    cofN = ctx.J * ufl.inv(F).T * N
    J_s = ufl.sqrt(ufl.dot(cofN, cofN))
    I1 = ufl.tr(C_s)
    w_plain = mu / 2 * (I1 - 2 - 2 * ufl.ln(J_s)) + lmbda / 2 * (J_s - 1) ** 2
    disc = I1 ** 2 - 4 * J_s ** 2
    l1 = ufl.sqrt((I1 + ufl.sqrt(ufl.max_value(disc, DISC_MIN))) / 2)
    l2 = J_s / l1
    # natural width, dW_s/dl2 = 0: n = (L l1 + sqrt(L^2 l1^2 + 4 mu (mu + L l1^2))) / (2 (mu + L l1^2))
    n = (lmbda * l1 + ufl.sqrt(lmbda ** 2 * l1 ** 2 + 4 * mu * (mu + lmbda * l1 ** 2))) \
        / (2 * (mu + lmbda * l1 ** 2))
    tense = ufl.conditional(ufl.lt(l2, n), membrane_density(mu, lmbda, l1, n), w_plain)
    return ufl.conditional(ufl.gt(disc, DISC_MIN), ufl.conditional(ufl.gt(l1, 1.0), tense, 0.0), w_plain)


class TensionFieldSkin(_Form):
    NAME = "candidate:skin"
    CANDIDATE = "skin"

    def __init__(self, ctx, pattern=None, tissue=None):
        super().__init__(ctx, "skin.mu")
        self.density = tension_field_density(ctx, self.q, self.q)       # lambda_s = mu_s = q
        self.energy = T_S * self.density * ctx.ds("skin")                 # int_skin t_s W_s dA


class UpperPoleSkin(_Form):
    NAME = "candidate:skin_upper_pole"
    CANDIDATE = "skin_upper_pole"
    PHYSICS = "skin"
    PARAMETER = "skin_upper_pole.mu"
    EXTENDS = "skin"

    def __init__(self, ctx, pattern=None, tissue=None):
        super().__init__(ctx, self.PARAMETER)
        self.density = tension_field_density(ctx, self.q, self.q)       # lambda_u = mu_u = q
        self.energy = T_S * upper_pole(ctx.X) * self.density * ctx.ds("skin")   # int_skin [Z > 0] t_s W_s dA


def _module(cls):
    """The class itself serves as the module: NAME, CANDIDATE, structure,
    REPLACES_FIXED_BASE and Term."""
    cls.Term = cls
    return cls


CANDIDATE_FORMS = {c.CANDIDATE: _module(c) for c in (UniformBed, SharpCore, UpperPoleSprings,
                                                         TensionFieldSkin)}
# Other forms of a candidate's physics (pseudo_true.py --form PHYSICS=FORM).
OTHER_FORMS = {c.CANDIDATE: _module(c) for c in (UpperPoleCables, BuriedLobe)}
# Regional variations that extend a candidate (its form joined by '+').
EXTENSIONS = {c.CANDIDATE: _module(c) for c in (UpperPoleSkin,)}
# The forms that can replace a physics' candidate in a pseudo-true fit, by
# name: another form alone, or the candidate with a regional variation
# ("skin+skin_upper_pole"), their values fitted jointly.
ALTERNATIVE_FORMS = {**{n: [m] for n, m in OTHER_FORMS.items()},
                     **{f"{m.EXTENDS}+{n}": [CANDIDATE_FORMS[m.EXTENDS], m] for n, m in EXTENSIONS.items()}}


def physics_of_form(name):
    """The physics an ALTERNATIVE_FORMS entry stands for."""
    first = ALTERNATIVE_FORMS[name][0]
    return getattr(first, "PHYSICS", first.CANDIDATE)
