// SPDX-License-Identifier: LGPL-3.0-or-later
// Grid sequencing (src/solver/coarse_start.hpp): when it applies, that the transfer
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

namespace
{
/// Interpolate `field` (x -> u(x) in each row) into the finest level of the
/// ladder of case `c`, transfer it to the fine model and return the share of
/// fine nodes where the transfer equals field exactly (1e-13) and the worst
/// error.
template <class Field>
std::pair<double, double> transfer_error(const Config& c, Field field)
{
  auto fine = fixtures::make_model(c);
  CoarseStart cs(c, *fine);
  cs.finest_level_model().displacement()->interpolate(
      [&](auto&& x)
      {
        xt::xarray<double> v = xt::zeros<double>({std::size_t(3), x.shape(1)});
        for (std::size_t p = 0; p < x.shape(1); ++p)
        {
          const auto u = field(x(0, p), x(1, p), x(2, p));
          for (int i = 0; i < 3; ++i)
            v(i, p) = u[i];
        }
        return v;
      });
  cs.transfer_to(*fine);
  const auto X = fine->space()->tabulate_dof_coordinates(false);
  const auto u = fine->displacement()->x()->array();
  EXPECT_EQ(u.size(), X.size());
  std::size_t exact = 0;
  double worst = 0;
  for (std::size_t i = 0; i < X.size() / 3; ++i)
  {
    const auto ref = field(X[3 * i], X[3 * i + 1], X[3 * i + 2]);
    double err = 0;
    for (int k = 0; k < 3; ++k)
      err = std::max(err, std::abs(u[3 * i + k] - ref[k]));
    exact += err < 1e-13;
    worst = std::max(worst, err);
  }
  return {exact / static_cast<double>(X.size() / 3), worst};
}

// u = A X with u_x = 0 on the symmetry plane x = 0.
std::array<double, 3> affine(double x, double y, double z)
{
  return {0.01 * x, 0.02 * y - 0.01 * z, 0.03 * x + 0.005 * y};
}
} // namespace

TEST(CoarseStart, TransferFromTheCoarseP1MeshReproducesAnAffineField)
{
  // Exact at fine nodes inside the coarse polyhedron; outside it (the curved
  // skin, at most a chord's sagitta away) the value of the nearest coarse
  // point.
  Config c = fixtures::coarse_case(2, 0.008);
  c.set("solver.coarse_mesh_size", 0.016);
  c.set("solver.nested_levels", std::int64_t{0});
  ASSERT_EQ(nested_ladder(c).size(), 1u);
  const auto [exact, worst] = transfer_error(c, affine);
  EXPECT_GT(exact, 0.7);
  // |A| ~ 0.04, a skin node is less than 1 mm from the coarse polyhedron.
  EXPECT_LT(worst, 0.04 * 1e-3);
}

TEST(CoarseStart, TransferFromACurvedP2LevelReproducesAffineAndQuadraticFields)
{
  // The ladder's P2 level (16 mm) has curved skin cells: the transfer pulls
  // fine nodes back through their curved map. An affine field lies in the
  // isoparametric P2 space: exact wherever a node lies in a coarse cell. A
  // quadratic one is exact in the straight (affine) coarse cells.
  Config c = fixtures::coarse_case(2, 0.008);
  c.set("solver.coarse_mesh_size", 0.016);
  const auto ladder = nested_ladder(c);
  ASSERT_EQ(ladder.size(), 2u);
  EXPECT_EQ(ladder[1].order, 2);
  EXPECT_DOUBLE_EQ(ladder[1].mesh_size, 0.016);
  const auto [exact, worst] = transfer_error(c, affine);
  EXPECT_GT(exact, 0.75); // measured 0.79: the others are skin nodes just outside the coarse skin
  EXPECT_LT(worst, 0.04 * 1e-4); // the curved skin is much closer than the P1 polyhedron
  const auto [exact_q, worst_q] = transfer_error(
      c, [](double x, double y, double z) -> std::array<double, 3>
      { return {x * y, y * y - 2 * x * z, z * z + x * x}; });
  EXPECT_GT(exact_q, 0.45); // measured 0.52
  EXPECT_LT(worst_q, 0.07 * 0.07 * 0.05);
}

TEST(CoarseStart, SameEquilibriumAsFromRestInFewerFineNewtonIterations)
{
  Config c = fixtures::coarse_case(1, 0.006);
  c.set("solver.coarse_mesh_size", 0.012);
  c.set("postures.names", std::vector<std::string>{"standing"});
  ASSERT_TRUE(coarse_start_applies(c));
  auto m = fixtures::make_model(c);
  ObservableProbe probe(*m, {0.0, c.number("geometry.H"), 0.0});
  NewtonSolver newton(*m, NewtonOptions::from(c));
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

TEST(CoarseStart, LadderHalvesTheMeshSizeWhileLevelsHaveFourTimesTheCoarseUnknowns)
{
  auto ladder = [](double h, int order, int refinements = 0, std::int64_t levels = 2)
  {
    Config c;
    c.set("geometry.mesh_size", h);
    c.set("geometry.order", std::int64_t(order));
    c.set("geometry.refinements", std::int64_t(refinements));
    c.set("solver.nested_levels", levels);
    std::vector<std::tuple<double, int, int>> out;
    for (const auto& l : nested_ladder(c))
      out.emplace_back(l.mesh_size, l.order, l.refinements);
    return out;
  };
  using L = std::vector<std::tuple<double, int, int>>;
  // Benchmark meshes (coarse P1 mesh 8 mm): 200k P2 tetrahedra (1.9 mm):
  // 7.6 mm P2 has 7 (8 / 7.6)^3 = 8.2x the coarse unknowns, 15.2 mm 1.0x.
  EXPECT_EQ(ladder(0.0019, 2), (L{{0.008, 1, 0}, {0.0076, 2, 0}, {0.0038, 2, 0}}));
  EXPECT_EQ(ladder(0.003, 2), (L{{0.008, 1, 0}, {0.006, 2, 0}}));
  EXPECT_EQ(ladder(0.0075, 2), (L{{0.008, 1, 0}}));        // 15 mm P2: 1.06x
  EXPECT_EQ(ladder(0.008, 1), L{});                        // the coarse mesh itself
  // P1 cases start from the coarse P1 mesh alone (an intermediate P1 level
  // made the 194k P1 solve slower).
  EXPECT_EQ(ladder(0.0019, 1), (L{{0.008, 1, 0}}));
  EXPECT_EQ(ladder(0.008, 1, 2), (L{{0.008, 1, 0}}));
  // Uniformly refined cases step down one refinement at a time (nested
  // meshes): 8 mm P2 refined twice, 7 x 64 = 448x the coarse unknowns.
  EXPECT_EQ(ladder(0.008, 2, 2), (L{{0.008, 1, 0}, {0.008, 2, 0}, {0.008, 2, 1}}));
  // solver.nested_levels bounds the intermediate meshes (the finest kept).
  EXPECT_EQ(ladder(0.0019, 2, 0, 1), (L{{0.008, 1, 0}, {0.0038, 2, 0}}));
  EXPECT_EQ(ladder(0.0019, 2, 0, 0), (L{{0.008, 1, 0}}));
}

TEST(CoarseStart, IntermediateP2LevelSameEquilibriumInFewerFineNewtonIterations)
{
  // P2 at 8 mm from the coarse P1 mesh (16 mm) directly, and through a P2
  // level at 16 mm: the same equilibrium, and the P2 level's start leaves
  // the fine Newton fewer iterations.
  Config c = fixtures::coarse_case(2, 0.008);
  c.set("solver.coarse_mesh_size", 0.016);
  c.set("postures.names", std::vector<std::string>{"standing"});
  auto m = fixtures::make_model(c);
  ObservableProbe probe(*m, {0.0, c.number("geometry.H"), 0.0});
  NewtonSolver newton(*m, NewtonOptions::from(c));
  const Posture standing = named_posture("standing");
  std::vector<double> u[2];
  int fine_newton[2];
  for (std::int64_t levels : {0, 1})
  {
    c.set("solver.nested_levels", levels);
    CoarseStart cs(c, *m);
    ASSERT_EQ(cs.num_levels(), static_cast<std::size_t>(levels + 1));
    const PostureResult r = solve_posture(*m, newton, probe, standing, c, &cs);
    ASSERT_TRUE(r.coarse.used) << r.coarse.reason;
    ASSERT_EQ(r.coarse.level_newton_iterations.size(), cs.num_levels());
    EXPECT_EQ(r.path.failed_steps, 0);
    fine_newton[levels] = r.path.newton_iterations;
    auto a = m->displacement()->x()->array();
    u[levels].assign(a.begin(), a.end());
  }
  const auto [diff, scale] = fixtures::max_difference(u[1], u[0]);
  EXPECT_GT(scale, 1e-3);
  EXPECT_LT(diff, 1e-8 * scale);
  EXPECT_LT(fine_newton[1], fine_newton[0]) << "through the P2 level " << fine_newton[1]
                                            << ", from the P1 mesh " << fine_newton[0];
}

namespace
{
/// The standing posture of the coarse default case.
struct WarmStartCase
{
  Config c = fixtures::coarse_case();
  std::unique_ptr<Model> m = fixtures::make_model(c);
  ObservableProbe probe{*m, {0.0, c.number("geometry.H"), 0.0}};
  NewtonSolver newton{*m, NewtonOptions::from(c)};
  Posture standing = named_posture("standing");
  /// A guess setting u to `u` (local values).
  Guess guess(const std::vector<T>& u)
  {
    Guess g;
    g.set = [u](Model& model, std::string&)
    {
      auto x = model.displacement()->x()->mutable_array();
      std::copy(u.begin(), u.end(), x.begin());
      model.displacement()->x()->scatter_fwd();
      return true;
    };
    return g;
  }
  std::vector<T> u() const
  {
    auto a = m->displacement()->x()->array();
    return {a.begin(), a.end()};
  }
};
} // namespace

// The one fallback (solve_at_full_load): an admissible guess is used and
// Newton converges from it at full load; a guess that inverts an element,
// or one whose energy is not below that of u = 0, is refused and the load
// ramped from u = 0, to the same equilibrium.
TEST(SolverWarmStart, UsesOnlyAdmissibleGuessesAndFallsBackToTheRamp)
{
  WarmStartCase w;
  const PostureResult rest = solve_posture(*w.m, w.newton, w.probe, w.standing, w.c);
  EXPECT_FALSE(rest.converged_from_guess);
  const std::vector<T> solution = w.u();

  // The equilibrium itself, slightly disturbed: used, converged from it.
  std::vector<T> near = solution;
  for (auto& x : near)
    x *= 0.99;
  const PostureResult warm = solve_posture(*w.m, w.newton, w.probe, w.standing, w.c, w.guess(near));
  EXPECT_TRUE(warm.converged_from_guess);
  EXPECT_EQ(warm.path.steps, 1);
  EXPECT_EQ(warm.path.failed_steps, 0);
  EXPECT_LT(warm.path.newton_iterations, rest.path.newton_iterations);
  EXPECT_NEAR(warm.observables.nipple[2], rest.observables.nipple[2], 1e-9);

  // Inverted elements: u = -2 X flips every element (det F = -1).
  std::vector<T> inverted(solution.size());
  const auto X = w.m->space()->tabulate_dof_coordinates(false);
  for (std::size_t i = 0; i < inverted.size(); ++i)
    inverted[i] = -2 * X[i];
  // Energy above u = 0's: the equilibrium mirrored (the breast lifted
  // against gravity).
  std::vector<T> lifted = solution;
  for (auto& x : lifted)
    x = -x;
  for (const auto* bad : {&inverted, &lifted})
  {
    w.m->displacement()->x()->set(0.0);
    set_gravity(*w.m, gravity_vector(0.0, w.c.number("gravity.g")));
    const WarmStartReport r = solve_at_full_load(*w.m, w.newton, w.guess(*bad), LoadStepOptions{},
                                                 "test", 1.0);
    EXPECT_FALSE(r.used);
    EXPECT_FALSE(r.converged);
    EXPECT_FALSE(r.reason.empty());
    EXPECT_GE(r.path.steps, 1);
    const PostureResult fallback = solve_posture(*w.m, w.newton, w.probe, w.standing, w.c, w.guess(*bad));
    EXPECT_FALSE(fallback.converged_from_guess);
    EXPECT_EQ(fallback.path.newton_iterations, rest.path.newton_iterations);
    const auto [diff, scale] = fixtures::max_difference(w.u(), solution);
    EXPECT_LT(diff, 1e-8 * scale);
  }
}

// The coarse start's guess goes through the same check: a guess is "used"
// only when admissible, and the report says why not otherwise.
TEST(SolverWarmStart, InadmissibleGuessNamesTheReason)
{
  WarmStartCase w;
  set_gravity(*w.m, gravity_vector(0.0, w.c.number("gravity.g")));
  w.m->set_parameter("load", {1.0});
  w.m->displacement()->x()->set(0.0);
  const double e0 = w.m->energy();
  EXPECT_NE(inadmissible_guess(*w.m, e0).find("energy"), std::string::npos); // u = 0 itself
  const auto X = w.m->space()->tabulate_dof_coordinates(false);
  auto x = w.m->displacement()->x()->mutable_array();
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = -2 * X[i];
  EXPECT_NE(inadmissible_guess(*w.m, e0).find("det F"), std::string::npos);
}
