#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""The truth effects outside breastsim's candidate library
(bench/truth/forms_truth OUTSIDE_LIBRARY) against closed forms, on the P2
half cap at 14 mm (V the half cap's volume pi H (3 R^2 + H^2) / 12):

1. every one is zero at its null amplitude (inclusion contrast 1, gradient
   beta = 0, the laws' k2 -> the neo-Hookean limit, Mooney-Rivlin f = 0,
   sliding base c = 0) under a general deformation;
2. stiff_inclusion, u = e X (F = (1 + e) I, W uniform):
   E = A W((1 + e) I) int g dV,  int g dV = 4 pi a1 a2 a3 (1/6 - 1/pi^2)
   for an ellipsoid inside the body (int_0^1 cos^2(pi s/2) s^2 ds), turned
   by psi and phi; and every site's centre range lies at least 7 mm inside
   the skin;
3. stiffness_gradient along base_apex, u = e X: t = Y/H,
   E = W((1 + e) I) int_0^H A(y) (exp(beta (y/H - t_mean)) - 1) dy,
   A(y) = pi/2 (Rs^2 - (y - H + Rs)^2) the half cap's section, t_mean its
   mean of y/H (1D quadrature);
4. strain_stiffening and mooney_rivlin: zero under any dilation (I1bar =
   I2bar = 3); under the isochoric stretch F = diag(l^-1/2, l, l^-1/2):
   I1bar = l^2 + 2/l, I2bar = 2 l + 1/l^2, and E = V times
   yeoh   mu/2 k2 (x^2 + c3 x^3),
   gent   -mu/(4 k2) ln(1 - 2 k2 x) - mu/2 x,
   demiray mu/(4 k2) (exp(2 k2 x) - 1) - mu/2 x,      x = I1bar - 3,
   MR     f mu/2 (I2bar - I1bar),  f = r / (1 + r);
   the laws agree with mu/2 k2 x^2 to first order as x -> 0;
5. sliding_base, u = (a_x, 0, a_z) constant: E = c_mean/2 (a a_x^2 +
   a_z^2 / a) A_base (c's area mean is c_mean), A_base = pi R^2 / 2; its
   profile's mean <w> = w_rim + (1 - w_rim) / (n + 1); and a P1 solve in the
   standing posture keeps u_y = 0 on the base while the base slides (u_z != 0).

Run: /usr/bin/python3 tests/truth/test_outside_effects.py SOURCE_DIR
"""
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve() / "bench" / "truth"))

import numpy as np  # noqa: E402
from scipy.integrate import quad  # noqa: E402

from forms_truth import OUTSIDE_LIBRARY, physics_of, tissue  # noqa: E402
from forms_truth import (mooney_rivlin, sliding_base, stiff_inclusion,  # noqa: E402
                         stiffness_gradient, strain_stiffening)
from forms_truth.context import Context  # noqa: E402
from geometry import TAGS, build_half_cap  # noqa: E402
import problem  # noqa: E402

R, H = 0.07, 0.06
RS = (R * R + H * H) / (2 * H)
V_HALF = math.pi * H * (3 * R * R + H * H) / 12
MU, LAMBDA = 500.0, 2000.0
failures = []


def check(name, got, want, rtol, atol=0.0):
    ok = abs(got - want) <= rtol * abs(want) + atol
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {got:.6g} against {want:.6g} (rtol {rtol:g}, atol {atol:g})")
    if not ok:
        failures.append(name)


def energy(ctx, term, u_of_x):
    ctx.u.interpolate(u_of_x)
    return ctx.integrate(term.energy)


def w_dilation(e):
    """W((1 + e) I), eq. (5)."""
    return MU / 2 * (3 * (1 + e) ** 2 - 3 - 2 * math.log((1 + e) ** 3)) + LAMBDA / 2 * ((1 + e) ** 3 - 1) ** 2


def general(x):
    """A smooth, non-affine displacement."""
    return np.stack([0.03 * x[0] * x[1] / H + 0.002 * x[0], 0.05 * x[2] - 0.04 * x[1], 0.02 * x[0] + 0.03 * x[1]])


def isochoric(lam):
    """u = (F - I) X, F = diag(lam^-1/2, lam, lam^-1/2) (J = 1)."""
    G = np.diag([lam ** -0.5, lam, lam ** -0.5]) - np.eye(3)
    return lambda x: G @ x


def registry():
    names = [m.NAME for m in OUTSIDE_LIBRARY]
    expect = {"stiff_inclusion": "tissue_field", "stiffness_gradient": "tissue_field",
              "strain_stiffening": "tissue_law", "mooney_rivlin": "tissue_law", "sliding_base": "base_condition"}
    got = {n: physics_of(n) for n in names}
    if got != expect or any(m.CANDIDATE is not None for m in OUTSIDE_LIBRARY):
        failures.append(f"registry: {got}")
    print(f"{'ok  ' if got == expect else 'FAIL'} registry: {got}")


def inclusion(ctx, tis):
    rng = np.random.default_rng(5)
    p = stiff_inclusion.draw_pattern(rng, "lateral_upper", "stiff")
    p.update({"cx": 0.025, "cy": 0.025, "cz": 0.0, "r1": 0.9, "r2": 0.8, "r3": 1 / 0.72,
              "psi_deg": 20.0, "phi_deg": 30.0, "contrast": 3.0})
    term = stiff_inclusion.Term(ctx, p, tis)
    term.set_strength(0.022)          # semi-axes 19.8, 17.6, 30.6 mm: inside the half cap
    e = 0.01
    vg = 4 * math.pi * float(np.prod(term.axes)) * (1 / 6 - 1 / math.pi ** 2)
    check("inclusion, int g dV", ctx.integrate(term.g * ctx.dx), vg, 0.01)
    check("inclusion, uniform dilation", energy(ctx, term, lambda x: e * x), 2.0 * w_dilation(e) * vg, 0.01)
    term.set_pattern({**p, "contrast": 1.0})
    check("inclusion, contrast 1 (null)", energy(ctx, term, general), 0.0, 0.0, 1e-300)
    # every site's centre range lies >= 7 mm inside the skin sphere
    worst = min(RS - math.dist((x, y, z), (0.0, H - RS, 0.0))
                for r in stiff_inclusion.RANGES_SITE.values()
                for x in r["cx"] for y in r["cy"] for z in r["cz"])
    print(f"{'ok  ' if worst >= 0.007 else 'FAIL'} inclusion, least depth of a centre under the skin: "
          f"{worst * 1e3:.2f} mm (>= 7 mm)")
    if worst < 0.007:
        failures.append("inclusion centre depth")


def gradient(ctx, tis):
    p = {"direction": "base_apex", "sign": 1, "tilt_deg": 0.0, "tilt_azimuth_deg": 0.0}
    term = stiffness_gradient.Term(ctx, p, tis)
    beta, e = math.log(3.0), 0.01

    def section(y):
        return math.pi / 2 * (RS * RS - (y - H + RS) ** 2)
    vol = quad(section, 0, H)[0]
    t_mean = quad(lambda y: section(y) * y / H, 0, H)[0] / vol
    check("gradient, t_mean (base_apex)", float(term.t_mean.value), t_mean, 2e-3)
    term.set_strength(beta)
    want = w_dilation(e) * quad(lambda y: section(y) * (math.exp(beta * (y / H - t_mean)) - 1), 0, H)[0]
    check("gradient, uniform dilation, ratio 3", energy(ctx, term, lambda x: e * x), want, 0.01)
    # the ratio across the breast is exp(beta): t spans [0, 1]
    d = term.describe(beta)
    check("gradient, ratio across", d["stiffness_factor_range"][1] / d["stiffness_factor_range"][0], 3.0, 1e-12)
    for direction in stiffness_gradient.DIRECTIONS:
        for sign in (1, -1):
            term.set_pattern({**p, "direction": direction, "sign": sign, "tilt_deg": 15.0, "tilt_azimuth_deg": 70.0})
            term.beta.value = 0.0
            check(f"gradient {direction} {sign:+d}, beta = 0 (null)", energy(ctx, term, general), 0.0, 0.0, 1e-300)


def laws(ctx, tis):
    lam, mu = 1.15, MU
    I1, I2 = lam ** 2 + 2 / lam, 2 * lam + 1 / lam ** 2
    x = I1 - 3
    k2, c3 = 0.4, 0.6
    want = {"yeoh": mu / 2 * k2 * (x ** 2 + c3 * x ** 3),
            "gent": -mu / (4 * k2) * math.log(1 - 2 * k2 * x) - mu / 2 * x,
            "demiray": mu / (4 * k2) * (math.exp(2 * k2 * x) - 1) - mu / 2 * x}
    for law in strain_stiffening.LAWS:
        term = strain_stiffening.Term(ctx, {"law": law, "c3": c3}, tis)
        term.set_strength(k2)
        check(f"{law}, isochoric stretch {lam}", energy(ctx, term, isochoric(lam)), V_HALF * want[law], 2e-3)
        check(f"{law}, dilation (I1bar = 3)", energy(ctx, term, lambda X: 0.03 * X), 0.0, 0.0, 1e-9)
        check(f"{law}, F = I", energy(ctx, term, lambda X: 0.0 * X), 0.0, 0.0, 1e-300)
        # the nonlinearity: W_law - mu/2 x = mu/2 k2 x^2 (1 + O(x))
        small = 1.01
        xs = small ** 2 + 2 / small - 3
        got = energy(ctx, term, isochoric(small)) / (V_HALF * mu / 2 * k2 * xs ** 2)
        check(f"{law}, leading term mu/2 k2 x^2 at x = {xs:.2e}", got, 1.0, 0.01)
    term = strain_stiffening.Term(ctx, {"law": "yeoh", "c3": c3}, tis)
    term.k2.value = 0.0
    check("yeoh, k2 = 0 (null)", energy(ctx, term, general), 0.0, 0.0, 1e-300)

    mr = mooney_rivlin.Term(ctx, {}, tis)
    r = 1.5
    mr.set_strength(r)
    f = r / (1 + r)
    check(f"Mooney-Rivlin, isochoric stretch {lam}", energy(ctx, mr, isochoric(lam)),
          V_HALF * f * mu / 2 * (I2 - I1), 2e-3)
    check("Mooney-Rivlin, dilation (I1bar = I2bar = 3)", energy(ctx, mr, lambda X: 0.03 * X), 0.0, 0.0, 1e-9)
    check("Mooney-Rivlin, describe: 2 (C10 + C01) = mu", 2 * sum(mr.describe(r)[k] for k in ("C10_Pa", "C01_Pa")),
          mu, 1e-12)
    mr.f.value = 0.0
    check("Mooney-Rivlin, f = 0 (null)", energy(ctx, mr, general), 0.0, 0.0, 1e-300)


def sliding(ctx):
    p = {"n": 2.0, "w_rim": 0.05, "a": 1.6}
    term = sliding_base.Term(ctx, p)
    check("sliding base, <w> = w_rim + (1 - w_rim)/(n + 1)", term.mean_w, 0.05 + 0.95 / 3, 2e-3)
    q = 2e-6
    term.set_strength(q)
    a = np.array([0.002, 0.0, -0.003])
    const = lambda x: np.tile(a[:, None], (1, x.shape[1]))
    check("sliding base, constant tangential u", energy(ctx, term, const),
          0.5 / q * (1.6 * a[0] ** 2 + a[2] ** 2 / 1.6) * math.pi * R * R / 2, 2e-3)
    term.c_mean.value = 0.0
    check("sliding base, c = 0 (null)", energy(ctx, term, general), 0.0, 0.0, 1e-300)


def sliding_solve(mesh, facets):
    """P1 standing solve: u_y = 0 on the base, the base slides in z."""
    ctx = Context(mesh, facets, TAGS, R, H, degree=1)
    prob = problem.Problem(ctx, [("sliding_base", {"n": 2.0, "w_rim": 0.05, "a": 1.0})])
    prob.configure({"mu": MU, "lambda": LAMBDA}, [("sliding_base", {"n": 2.0, "w_rim": 0.05, "a": 1.0})],
                   {"sliding_base": 2e-6})
    u = prob.solve_postures([{"name": "standing", "theta_deg": 0.0}], 970.0)[0].reshape(-1, 3)
    X = ctx.V.tabulate_dof_coordinates()
    base = np.abs(X[:, 1]) < 1e-9
    print(f"sliding base, standing: max |u_y| on the base {np.abs(u[base, 1]).max():.3g} m, "
          f"max |u_z| on the base {np.abs(u[base, 2]).max():.3g} m")
    if not (np.abs(u[base, 1]).max() == 0.0 and np.abs(u[base, 2]).max() > 1e-4):
        failures.append("sliding base: the base is not held normally or does not slide")


if __name__ == "__main__":
    registry()
    mesh, facets = build_half_cap(R, H, 0.014, order=2)
    ctx = Context(mesh, facets, TAGS, R, H, degree=2)
    tis = tissue.Term(ctx)
    tis.set(MU, LAMBDA)
    inclusion(ctx, tis)
    gradient(ctx, tis)
    laws(ctx, tis)
    sliding(ctx)
    sliding_solve(mesh, facets)
    if failures:
        print(f"FAILED: {failures}")
        sys.exit(1)
    print("all passed")
