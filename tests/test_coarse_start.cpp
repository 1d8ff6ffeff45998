// Grid sequencing (src/coarse_start.hpp): when it applies, that the transfer
// reproduces the coarse field at the fine nodes, and that a posture solved
// from the coarse solution is the same equilibrium as one solved from rest,
// in fewer fine Newton iterations.
#include "coarse_start.hpp"
#include "fixtures.hpp"
#include "posture.hpp"
#include <gtest/gtest.h>

using namespace breastsim;

TEST(CoarseStart, AppliesOnlyToMeshesWithFourTimesTheCoarseUnknowns)
{
  auto applies = [](double h, int order, int refinements, bool on = true)
  {
    Config c;
    c.set("geometry.mesh_size", h);
    c.set("geometry.order", std::int64_t(order));
    c.set("geometry.refinements", std::int64_t(refinements));
    c.set("solver.coarse_start", on);
    return coarse_start_applies(c);
  };
  // Default coarse mesh size 0.008 m = the default case's own mesh size.
  EXPECT_FALSE(applies(0.008, 1, 0));
  EXPECT_FALSE(applies(0.0055, 1, 0)); // (8 / 5.5)^3 = 3.1
  EXPECT_TRUE(applies(0.005, 1, 0));   // 4.1
  EXPECT_FALSE(applies(0.012, 2, 0));  // 7 (8 / 12)^3 = 2.1
  EXPECT_TRUE(applies(0.008, 2, 0));   // 7
  EXPECT_TRUE(applies(0.008, 1, 1));   // 8
  EXPECT_FALSE(applies(0.003, 2, 0, false));
}

TEST(CoarseStart, TransferReproducesAnAffineCoarseField)
{
  // u = A X with u_x = 0 on the symmetry plane x = 0: interpolation is exact
  // at fine nodes inside the coarse polyhedron; outside it (the curved skin,
  // at most a chord's sagitta away) the value of the nearest coarse point.
  Config c = fixtures::coarse_case(2, 0.008);
  c.set("solver.coarse_mesh_size", 0.016);
  auto fine = fixtures::make_model(c);
  CoarseStart cs(c, *fine);
  const double A[3][3] = {{0.01, 0, 0}, {0, 0.02, -0.01}, {0.03, 0.005, 0}};
  auto affine = [&](auto&& x)
  {
    xt::xarray<double> v = xt::zeros<double>({std::size_t(3), x.shape(1)});
    for (std::size_t p = 0; p < x.shape(1); ++p)
      for (int i = 0; i < 3; ++i)
        v(i, p) = A[i][0] * x(0, p) + A[i][1] * x(1, p) + A[i][2] * x(2, p);
    return v;
  };
  cs.coarse_model().displacement()->interpolate(affine);
  cs.transfer_to(*fine);

  const auto X = fine->space()->tabulate_dof_coordinates(false);
  const auto u = fine->displacement()->x()->array();
  ASSERT_EQ(u.size(), X.size());
  std::size_t exact = 0;
  double worst = 0;
  for (std::size_t i = 0; i < X.size() / 3; ++i)
  {
    double err = 0;
    for (int k = 0; k < 3; ++k)
    {
      const double ref = A[k][0] * X[3 * i] + A[k][1] * X[3 * i + 1] + A[k][2] * X[3 * i + 2];
      err = std::max(err, std::abs(u[3 * i + k] - ref));
    }
    exact += err < 1e-13;
    worst = std::max(worst, err);
  }
  const double n = static_cast<double>(X.size() / 3);
  EXPECT_GT(exact / n, 0.7) << exact << " of " << n << " nodes exact";
  // |A| ~ 0.04, a skin node is less than 1 mm from the coarse polyhedron.
  EXPECT_LT(worst, 0.04 * 1e-3);
}

TEST(CoarseStart, SameEquilibriumAsFromRestInFewerFineNewtonIterations)
{
  Config c = fixtures::coarse_case(1, 0.006);
  c.set("solver.coarse_mesh_size", 0.012);
  c.set("postures.names", std::vector<std::string>{"standing"});
  ASSERT_TRUE(coarse_start_applies(c));
  auto m = fixtures::make_model(c);
  ObservableProbe probe(*m, {0.0, c.number("geometry.H"), 0.0});
  NewtonSolver newton(*m, newton_options(c));
  const Posture standing = named_posture("standing");

  const PostureResult rest = solve_posture(*m, newton, probe, standing, c);
  const std::vector<T> u_rest(m->displacement()->x()->array().begin(),
                              m->displacement()->x()->array().end());
  ASSERT_FALSE(rest.coarse.used);

  CoarseStart cs(c, *m);
  // The guess itself: admissible, constraints exact, below the neutral energy.
  m->displacement()->x()->set(0.0);
  set_gravity(*m, gravity_vector(0.0, c.number("gravity.g")));
  m->set_parameter("load", {1.0});
  const CoarseGuessReport g = cs.guess(*m, gravity_vector(0.0, c.number("gravity.g")));
  ASSERT_TRUE(g.used) << g.reason;
  EXPECT_GT(g.newton_iterations, 0);
  EXPECT_GT(m->min_detF(), 0.0);
  EXPECT_LT(m->energy(), 0.0);
  const auto marks = m->constrained_markers();
  const auto guess = m->displacement()->x()->array();
  for (std::size_t i = 0; i < marks.size(); ++i)
    if (marks[i])
      ASSERT_EQ(guess[i], 0.0) << "constrained dof " << i;

  const PostureResult seq = solve_posture(*m, newton, probe, standing, c, &cs);
  ASSERT_TRUE(seq.coarse.used);
  EXPECT_EQ(seq.path.failed_steps, 0);
  EXPECT_LT(seq.path.newton_iterations, rest.path.newton_iterations);
  const auto u_seq = m->displacement()->x()->array();
  const auto [diff, scale] = fixtures::max_difference(u_seq, u_rest);
  EXPECT_LT(diff, 1e-8 * scale) << "max |u_seq - u_rest| = " << diff << " of max |u| " << scale;
  EXPECT_NEAR(seq.observables.nipple[2], rest.observables.nipple[2], 1e-9);
  EXPECT_NEAR(seq.observables.volume, rest.observables.volume, 1e-12);
}
