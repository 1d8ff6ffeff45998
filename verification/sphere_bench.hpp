// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Reference benchmark: a thick-walled sphere A <= |X| <= B of the
// compressible neo-Hookean tissue (paper eq. 5), inflated by a dead inner
// pressure p0 (nominal traction), outer surface free. The radially symmetric
// solution r(R) of the same energy is integrated as an ODE (sphere_reference)
// and compared with the finite-element solution on an octant of the shell
// (solve_sphere_bench, verification/forms/sphere_bench.py). docs/VERIFICATION.md.
#include <cstdint>
#include <mpi.h>

namespace breastsim
{
struct SphereBenchSpec
{
  double A = 0.01, B = 0.02;     ///< inner / outer reference radius [m]
  double mu = 400, lambda = 8000; ///< tissue moduli [Pa] (the model's defaults)
  double p0 = 400;               ///< nominal inner pressure [Pa]
};

/// Deformed inner and outer radii a = r(A), b = r(B) of the radial solution:
///   lambda_r = r', lambda_t = r / R, J = lambda_r lambda_t^2,
///   P_r = mu (lambda_r - 1/lambda_r) + lambda (J - 1) lambda_t^2,
///   P_t = mu (lambda_t - 1/lambda_t) + lambda (J - 1) lambda_r lambda_t,
///   dP_r/dR + 2/R (P_r - P_t) = 0,  P_r(A) = -p0,  P_r(B) = 0,
/// integrated in (r, P_r) by classical RK4 with `steps` steps, shooting on
/// a (bisection). Throws std::runtime_error if no bracket is found.
struct SphereReference
{
  double a = 0, b = 0;
};
SphereReference sphere_reference(const SphereBenchSpec& s, int steps = 4000);

/// The incompressible limit (lambda -> infinity) of the same problem in
/// closed form: the isochoric radial map r(R) = (R^3 + a^3 - A^3)^(1/3),
/// and the radial equilibrium integrated from b to a for the neo-Hookean
/// law (eq. 5 at J = 1: W = mu/2 (I1 - 3)), with hoop stretch l = r/R,
///   P(a) = int_lb^la W'(l) / (l^3 - 1) dl = 2 mu [1/lb - 1/la + 1/(4 lb^4) - 1/(4 la^4)]
/// (Cauchy pressure on the deformed inner surface). The dead nominal load
/// gives p0 = la^2 P(a); a solved by bisection. Throws std::runtime_error
/// if p0 needs a > 4A.
SphereReference incompressible_sphere_reference(const SphereBenchSpec& s);

struct SphereBenchResult
{
  std::int64_t cells = 0, dofs = 0;
  double u_inner = 0, u_outer = 0; ///< mean radial displacement on the inner / outer surface [m]
  int newton_iterations = 0;       ///< total over the load steps
  double seconds = 0;
};

/// The octant mesh of the shell by gmsh (target size mesh_size; P2:
/// curved 10-node cells), symmetry planes sliding, the pressure applied in
/// `load_steps` equal increments, Newton (LU) at each. mixed: the
/// Taylor-Hood P2-P1 (u, p) formulation (order 2, lambda > 0; InputError
/// otherwise). Collective.
SphereBenchResult solve_sphere_bench(const SphereBenchSpec& s, int order, double mesh_size,
                                     MPI_Comm comm, int load_steps = 4, bool mixed = false);
} // namespace breastsim
