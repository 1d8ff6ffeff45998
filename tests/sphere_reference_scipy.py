# SPDX-License-Identifier: LGPL-3.0-or-later
# Independent cross-check (scipy solve_bvp, not part of ctest) of sphere_reference()
# in verification/sphere_bench.cpp: the pressurised thick sphere of the energy (eq. 5)
# W = mu/2 (I1 - 3 - 2 ln J) + lam/2 (J - 1)^2, radial r(R), dead inner pressure p0.
# Usage: /usr/bin/python3 tests/sphere_reference_scipy.py A B mu lambda p0 [tol]
import sys
import numpy as np
from scipy.integrate import solve_bvp
A, B, mu, lam, p0 = [float(s) for s in sys.argv[1:6]]
def stresses(R, r, s):
    lt = r / R; J = s * lt**2
    Pr = mu * (s - 1 / s) + lam * (J - 1) * lt**2
    Pt = mu * (lt - 1 / lt) + lam * (J - 1) * s * lt
    return Pr, Pt
def rhs(R, y):
    r, s = y
    lt = r / R; J = s * lt**2
    # d/dR Pr(s, r, R) = dPr/ds s' + dPr/dr r' + dPr/dR = -2/R (Pr - Pt)
    Pr, Pt = stresses(R, r, s)
    dPr_ds = mu * (1 + 1 / s**2) + lam * lt**4
    # d/dr and d/dR through lt = r/R: dPr/dlt = lam (dJ/dlt lt^2 + (J-1) 2 lt), dJ/dlt = 2 s lt
    dPr_dlt = lam * (2 * s * lt * lt**2 + (J - 1) * 2 * lt)
    dlt_dR = (s - lt) / R  # total derivative of r/R along the solution
    sp = (-2 / R * (Pr - Pt) - dPr_dlt * dlt_dR) / dPr_ds
    return np.vstack([s, sp])
def bc(ya, yb):
    return np.array([stresses(A, ya[0], ya[1])[0] + p0, stresses(B, yb[0], yb[1])[0]])
R = np.linspace(A, B, 200)
y0 = np.vstack([R * 1.1, np.ones_like(R)])
sol = solve_bvp(rhs, bc, R, y0, tol=float(sys.argv[6]) if len(sys.argv) > 6 else 1e-8, bc_tol=1e-10, max_nodes=200000)
print(sol.status, sol.message)
print("a/A = %.12f  b/B = %.12f  u_inner = %.12e  u_outer = %.12e" % (sol.sol(A)[0] / A, sol.sol(B)[0] / B, sol.sol(A)[0] - A, sol.sol(B)[0] - B))
