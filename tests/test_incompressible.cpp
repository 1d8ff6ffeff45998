// SPDX-License-Identifier: LGPL-3.0-or-later
// Nearly incompressible tissue (docs/VERIFICATION.md, "Nearly incompressible
// tissue"): the mixed Taylor-Hood P2-P1 formulation against the displacement
// formulation, on a manufactured solution at lambda / mu = 1e3
// (verification/mms_mixed) and on the pressurised thick sphere in the
// incompressible limit (verification/sphere_bench, closed form).
//
// MMS, nested red-refined 16 mm cap (566, 4528, 36224 cells), lambda/mu = 1e3,
// default u_ex (A = 6e-5 m, L = 0.16 m, kappa = 1), measured
// (IncompressibleMms.LongMixedOrdersAtLambdaOverMu1e3, 3.7-5 min):
//   mixed P2-P1: u L2 3.019, 3.037; u H1 1.993, 2.009; p L2 1.998, 2.057;
//   least-squares slopes 3.028, 2.001, 2.027.
// The divergence-free u_ex with a large quadratic pressure (kappa = 0, A =
// 3e-4 m, L = 0.08 m) gives u orders above theory on these meshes (3.196 /
// 2.145 from level 0 to 1): IncompressibleMms.LongSurplusFollowsThePressure.
#include "config.hpp"
#include "fixtures.hpp"
#include "errors.hpp"
#include "mms_mixed.hpp"
#include "sphere_bench.hpp"
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

using namespace breastsim;

namespace
{
/// The default case with lambda = ratio * mu.
Config tissue_at(double ratio)
{
  Config c;
  c.set("tissue.lambda", ratio * c.number("tissue.mu"));
  return c;
}

IncompressibleMmsStudy run(const Config& c, bool mixed, int order, int levels,
                           const IncompressibleMmsSetup& setup = {})
{
  auto s = incompressible_mms_study(c, mixed, order, 0.016, levels, MPI_COMM_WORLD, setup);
  std::printf("%s", mms_table(s).c_str());
  return s;
}

/// The divergence-free u_ex whose pressure is the quadratic part of J:
/// p_ex ~ lambda (A / L)^2 = 3.75 mu |grad u_ex| at A = 3e-4 m, L = 0.08 m.
IncompressibleMmsSetup quadratic_pressure(double amplitude, double kappa = 0)
{
  IncompressibleMmsSetup setup;
  setup.amplitude = amplitude;
  setup.length = 0.08;
  setup.kappa = kappa;
  return setup;
}

/// Every observed order (and, from 3 levels, the least-squares slope)
/// within 0.1 of theory: u L2 3, u H1 2, p L2 2.
void expect_mixed_orders(const IncompressibleMmsStudy& s)
{
  for (std::size_t i = 0; i < s.order_l2.size(); ++i)
  {
    EXPECT_NEAR(s.order_l2[i], 3.0, 0.1);
    EXPECT_NEAR(s.order_h1[i], 2.0, 0.1);
    EXPECT_NEAR(s.order_p[i], 2.0, 0.1);
  }
  if (s.levels.size() >= 3)
  {
    EXPECT_NEAR(s.fit_l2, 3.0, 0.1);
    EXPECT_NEAR(s.fit_h1, 2.0, 0.1);
    EXPECT_NEAR(s.fit_p, 2.0, 0.1);
  }
}
} // namespace

// Two levels (~8 s): level 0 -> 1 at lambda / mu = 1e3 (measured 3.019,
// 1.993, 1.998; the tolerance 0.1 is the issue's).
TEST(IncompressibleMms, MixedOrdersAtLambdaOverMu1e3)
{
  const auto s = run(tissue_at(1e3), true, 2, 2);
  ASSERT_EQ(s.order_p.size(), 1u);
  expect_mixed_orders(s);
}

// Three levels (3.7-5 min; the finest has 168k unknowns, LU, 4.1 GB).
TEST(IncompressibleMms, LongMixedOrdersAtLambdaOverMu1e3)
{
  const auto s = run(tissue_at(1e3), true, 2, 3);
  ASSERT_EQ(s.order_p.size(), 2u);
  expect_mixed_orders(s);
}

// Where the pressure dominates the stress at a short length scale, the
// velocity error converges faster than theory from level 0 to 1 (the part
// set by the pressure's approximation outweighs u's own): the
// divergence-free u_ex with the quadratic pressure at A = 3e-4 m; a tenth
// of the amplitude (p_ex / 100, u_ex / 10) is at theory; a volumetric part
// (kappa = 10) makes the pressure large again and the surplus returns.
TEST(IncompressibleMms, LongSurplusFollowsThePressure)
{
  const auto c = tissue_at(1e3);
  const auto large = run(c, true, 2, 2, quadratic_pressure(3e-4));
  const auto small = run(c, true, 2, 2, quadratic_pressure(3e-5));
  const auto volumetric = run(c, true, 2, 2, quadratic_pressure(3e-5, 10));
  EXPECT_GT(large.order_l2[0], 3.1);
  EXPECT_GT(large.order_h1[0], 2.1);
  EXPECT_NEAR(small.order_l2[0], 3.0, 0.1);
  EXPECT_NEAR(small.order_h1[0], 2.0, 0.05);
  EXPECT_GT(volumetric.order_h1[0], 2.1);
}

// P1 displacement at lambda / mu = 1e3 locks: its orders stay far below 2
// and 1 over three levels, and on 36224 cells its H1 error is larger than
// the mixed formulation's on 566 cells (u_ex with the quadratic pressure,
// A = 3e-4 m).
TEST(IncompressibleMms, P1DisplacementLocksAtLambdaOverMu1e3)
{
  const auto d = run(tissue_at(1e3), false, 1, 3, quadratic_pressure(3e-4));
  const auto m = run(tissue_at(1e3), true, 2, 1, quadratic_pressure(3e-4));
  EXPECT_LT(d.order_l2.back(), 1.5);
  EXPECT_LT(d.order_h1.back(), 0.8);
  EXPECT_GT(d.levels.back().rel_h1, 5 * m.levels.front().rel_h1);
}

TEST(IncompressibleMms, MixedRefusesItsLimits)
{
  EXPECT_THROW(solve_incompressible_mms(tissue_at(1e3), true, 1, 0.016, 0, MPI_COMM_WORLD), InputError);
  EXPECT_THROW(solve_incompressible_mms(tissue_at(0), true, 2, 0.016, 0, MPI_COMM_WORLD), InputError);
}

// The closed form of the incompressible thick sphere is the limit of the
// compressible radial ODE (the same law, eq. 5): |a_ode - a_inc| ~ 1/lambda.
TEST(SphereIncompressible, ClosedFormIsTheLimitOfTheRadialOde)
{
  SphereBenchSpec s;
  const auto inc = incompressible_sphere_reference(s);
  // The closed form's own check: r^3 - R^3 is the same at both surfaces.
  EXPECT_NEAR(std::pow(inc.b, 3) - std::pow(s.B, 3), std::pow(inc.a, 3) - std::pow(s.A, 3), 1e-18);
  double previous = 1;
  for (double ratio : {1e2, 1e3, 1e4})
  {
    s.lambda = ratio * s.mu;
    const auto ode = sphere_reference(s);
    const double gap = std::abs(ode.a - inc.a) / (inc.a - s.A);
    std::printf("lambda/mu %g: a - A ODE %.9e, closed form %.9e (relative gap %.3e)\n", ratio,
                ode.a - s.A, inc.a - s.A, gap);
    EXPECT_LT(gap, previous / 5);
    previous = gap;
  }
  EXPECT_LT(previous, 1e-3);
}

// lambda / mu = 1e4 (nu = 0.49995): the mixed P2-P1 octant against the
// closed form. Measured (mean radial displacement, inner / outer surface):
// 8 mm -0.183 % / -0.234 %, 4 mm -0.070 % / -0.082 % (the ODE at this
// lambda is 1.7e-5 beyond the closed form). The displacement P2 octant on the
// same meshes does not converge (Newton stalls at |R| / |R_load| = 0.17;
// at lambda / mu = 1e3 at 3e-10, above the benchmark's 1e-11).
TEST(SphereIncompressible, MixedMatchesTheClosedFormAtLambdaOverMu1e4)
{
  SphereBenchSpec s;
  s.lambda = 1e4 * s.mu;
  const auto inc = incompressible_sphere_reference(s);
  double previous = 1;
  for (double h : {0.008, 0.004})
  {
    const auto m = solve_sphere_bench(s, 2, h, MPI_COMM_WORLD, 4, true);
    const double e_in = m.u_inner / (inc.a - s.A) - 1, e_out = m.u_outer / (inc.b - s.B) - 1;
    std::printf("mixed P2-P1, h %.0f mm, %lld cells, %lld unknowns: u_inner %.6e (%+.3f %%), "
                "u_outer %.6e (%+.3f %%) against the closed form %.6e, %.6e\n", 1e3 * h,
                (long long)m.cells, (long long)m.dofs, m.u_inner, 100 * e_in, m.u_outer, 100 * e_out,
                inc.a - s.A, inc.b - s.B);
    EXPECT_LT(std::abs(e_in), previous);
    previous = std::abs(e_in);
    EXPECT_LT(std::abs(e_out), 3e-3);
  }
  EXPECT_LT(previous, 1e-3);
}

// The other rows of docs/VERIFICATION.md's thick-sphere table (~10 s): the
// mixed octant at lambda / mu = 1e3, 4 mm (measured -0.057 % inner, +0.007 %
// outer against the incompressible closed form, -0.075 % inner against the
// radial ODE at 1e3), and the displacement P2 octant at lambda / mu = 1e4,
// whose Newton does not converge on the 8 and 4 mm meshes.
TEST(SphereIncompressible, MixedAt1e3AndDisplacementP2At1e4)
{
  SphereBenchSpec s;
  s.lambda = 1e3 * s.mu;
  const auto inc = incompressible_sphere_reference(s);
  const auto ode = sphere_reference(s);
  const auto m = solve_sphere_bench(s, 2, 0.004, MPI_COMM_WORLD, 4, true);
  const double e_in = m.u_inner / (inc.a - s.A) - 1, e_out = m.u_outer / (inc.b - s.B) - 1;
  const double e_in_ode = m.u_inner / (ode.a - s.A) - 1;
  std::printf("mixed P2-P1 at lambda/mu 1e3, 4 mm, %lld cells, %lld unknowns, %d Newton: u_inner "
              "%+.3f %%, u_outer %+.3f %% (u_inner against the radial ODE at 1e3: %+.3f %%)\n",
              (long long)m.cells, (long long)m.dofs, m.newton_iterations, 100 * e_in, 100 * e_out,
              100 * e_in_ode);
  EXPECT_LT(std::abs(e_in), 1e-3);
  EXPECT_LT(std::abs(e_out), 1e-3);
  s.lambda = 1e4 * s.mu;
  for (double h : {0.008, 0.004})
  {
    bool failed = false;
    try
    {
      solve_sphere_bench(s, 2, h, MPI_COMM_WORLD);
    }
    catch (const SolveError& e)
    {
      failed = true;
      std::printf("displacement P2 at lambda/mu 1e4, %.0f mm: %s\n", 1e3 * h, e.what());
    }
    EXPECT_TRUE(failed) << "h " << h;
  }
}

TEST(SphereIncompressible, MixedRefusesP1AndZeroLambda)
{
  SphereBenchSpec s;
  EXPECT_THROW(solve_sphere_bench(s, 1, 0.008, MPI_COMM_WORLD, 4, true), InputError);
  s.lambda = 0;
  EXPECT_THROW(solve_sphere_bench(s, 2, 0.008, MPI_COMM_WORLD, 4, true), InputError);
}

// The mixed model's Jacobian is the derivative of its residual (UFL
// derivative() of every term on the mixed space, composed): at a state w
// with u and p non-zero and a direction v (all entries, u and p),
//   |r(w + t v) - r(w) - t J(w) v| = O(t^2).
TEST(MixedModel, JacobianTaylorRemainder)
{
  auto c = fixtures::coarse_case(2, 0.02);
  c.set("tissue.lambda", 4e5);
  c.set("tissue.formulation", std::string("mixed"));
  c.set("skin.tension_only", 0.0); // the plain membrane: the relaxed one is only C1
  Model m(build_neutral_mesh(c, MPI_COMM_WORLD), Constraints{true, false}, TissueFormulation::mixed);
  apply_parameters(c, m);
  m.set_parameter("g_vec", {0.0, -4.0, -9.0});
  fixtures::perturb(m, 2e-3, 1);
  m.energy(); // w's u part = u
  PetscVec w0(m.create_vector()), v(m.create_vector()), w(m.create_vector()), r0(m.create_vector()),
      r1(m.create_vector()), Jv(m.create_vector());
  PetscMat J(m.create_matrix());
  {
    PetscVec state(dolfinx::la::petsc::create_vector_wrap(*m.state()->x()));
    VecCopy(state.get(), w0.get());
  }
  PetscInt n, lo;
  VecGetLocalSize(w0.get(), &n);
  VecGetOwnershipRange(w0.get(), &lo, nullptr);
  PetscScalar *a, *b;
  VecGetArray(w0.get(), &a);
  VecGetArray(v.get(), &b);
  for (PetscInt i = 0; i < n; ++i)
  {
    a[i] += 1e-4 * std::sin(0.37 * double(lo + i)); // p ~ 1e-4 Pa .. u noise 0.1 mm
    b[i] = 2e-4 * std::cos(0.11 * double(lo + i));
  }
  VecRestoreArray(w0.get(), &a);
  VecRestoreArray(v.get(), &b);
  // Constrained entries: 0 in w0 and in v (their rows are u - g, their
  // columns are not in J).
  m.set_displacement(w0.get());
  m.constrain_displacement();
  m.energy(); // w's u part = the constrained u
  {
    PetscVec state(dolfinx::la::petsc::create_vector_wrap(*m.state()->x()));
    VecCopy(state.get(), w0.get());
  }
  m.constrain_increment(v.get());
  ASSERT_GT(m.min_detF(), 0.0);
  m.assemble_residual(r0.get());
  m.assemble_jacobian(J.get());
  MatMult(J.get(), v.get(), Jv.get());
  std::vector<double> e;
  for (double t : {1.0, 0.5, 0.25, 0.125})
  {
    VecWAXPY(w.get(), t, v.get(), w0.get());
    m.set_displacement(w.get());
    m.assemble_residual(r1.get());
    VecAXPY(r1.get(), -1.0, r0.get());
    VecAXPY(r1.get(), -t, Jv.get());
    PetscReal norm;
    VecNorm(r1.get(), NORM_2, &norm);
    e.push_back(norm);
  }
  for (std::size_t k = 1; k < e.size(); ++k)
  {
    std::printf("t = %g: remainder %.3e, rate %.3f\n", std::pow(0.5, double(k)), e[k], std::log2(e[k - 1] / e[k]));
    EXPECT_NEAR(std::log2(e[k - 1] / e[k]), 2.0, 0.2);
  }
}

