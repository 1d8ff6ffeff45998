// SPDX-License-Identifier: LGPL-3.0-or-later
// The forward map of a diagnosis (point_evaluator.hpp): a posture left out
// adds nothing, a posture that cannot be solved is marked, not thrown, and
// its noise floor is the largest measured one (mesh_error.hpp); on posture
// groups the group that failed logs why. The held-out prediction solved
// (solved_held_out.hpp) follows the step fitted on the other postures and not
// the held-out posture's own Jacobian.
#include "case_groups.hpp"
#include "errors.hpp"
#include "evidence.hpp"
#include "fit_state.hpp"
#include "fixtures.hpp"
#include "linearised_refit.hpp"
#include "mesh_error.hpp"
#include "point_evaluator.hpp"
#include "recording.hpp"
#include "solved_held_out.hpp"
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <sstream>

using namespace breastsim;
using namespace breastsim::calibration;
using namespace breastsim::diagnosis;

namespace
{
/// Standing and supine, 12 points each in front of the chest, a nipple landmark.
Recording standing_and_supine()
{
  Recording rec;
  rec.noise_sigma = 5e-4;
  for (const auto& [name, theta] : {std::pair{"standing", 0.0}, std::pair{"supine", 90.0}})
  {
    RecordedPosture p{name, theta, {}, Point{0.0, 0.04, -0.01}};
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 4; ++k)
        p.points.push_back({0.015 * i, 0.03, -0.045 + 0.03 * k});
    rec.postures.push_back(p);
  }
  return rec;
}

/// A fit of tissue.mu at case `c` as a diagnosis keeps it: its value, the
/// whitened residuals and dr/d ln mu by a forward difference of step h.
FitState mu_fit(PointEvaluator& ev, const Config& c, const std::vector<Free>& frees, double h)
{
  FitState s;
  s.names = {"mu"};
  s.values = {c.number("tissue.mu")};
  const PointEvaluation e0 = ev(c), e1 = ev(config_at(c, frees, {std::log(s.values[0]) + h}));
  s.r = e0.r;
  s.distances = e0.distances;
  for (std::size_t i = 0; i < s.r.size(); ++i)
    s.J.push_back({(e1.r[i] - e0.r[i]) / h});
  return s;
}

/// A tissue far too soft for its load (tests/test_physics.cpp): standing fails.
Config too_soft()
{
  Config c = fixtures::coarse_case();
  c.set("tissue.mu", 1.0);
  c.set("tissue.lambda", 1.0);
  c.set("skin.thickness", 0.0);
  c.set("base.c", 1.0);
  c.set("solver.min_load_step", 1.0 / 16);
  c.validate();
  return c;
}
} // namespace

TEST(PointEvaluator, ExcludedPostureIsNotSolvedAndAddsNothing)
{
  const Recording rec = standing_and_supine();
  const Config c = fixtures::coarse_case();
  PointEvaluator ev(rec, MPI_COMM_WORLD);
  const PointEvaluation all = ev(c);
  ASSERT_EQ(all.solved, (std::vector<bool>{true, true}));
  ASSERT_EQ(all.r.size(), 2 * 12 + 2 * 3u);
  EXPECT_EQ(ev.posture_solves(), 2);
  EXPECT_GT(std::abs(all.distances[1][0]), 1e-6);

  ev.exclude(1);
  EXPECT_TRUE(ev.excluded(1));
  const PointEvaluation one = ev(c);
  EXPECT_EQ(one.solved, (std::vector<bool>{true, false}));
  EXPECT_EQ(ev.posture_solves(), 3); // only standing solved again
  for (std::size_t i = 0; i < 12; ++i)
  {
    EXPECT_NEAR(one.distances[0][i], all.distances[0][i], 1e-9);
    EXPECT_EQ(one.distances[1][i], 0.0);
    EXPECT_EQ(one.r[12 + i], 0.0); // posture 1's rows, after posture 0's
  }
  // Landmarks after all distances: standing's kept, supine's 0.
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_NEAR(one.raw[24 + k], all.raw[24 + k], 1e-9);
    EXPECT_EQ(one.raw[27 + k], 0.0);
    EXPECT_EQ(one.nipple_error[1][k], 0.0);
  }
  // Included again: solved as before.
  ev.include(1);
  const PointEvaluation back = ev(c);
  EXPECT_EQ(back.solved, (std::vector<bool>{true, true}));
  EXPECT_EQ(ev.posture_solves(), 5);
  EXPECT_NEAR(back.distances[1][0], all.distances[1][0], 1e-9);
}

TEST(PointEvaluator, TryEachMarksAPostureThatFailsInsteadOfThrowing)
{
  const Recording rec = standing_and_supine();
  PointEvaluator ev(rec, MPI_COMM_WORLD);
  EXPECT_THROW(ev(too_soft()), SolveError);
  const PointEvaluation e = ev.try_each(too_soft());
  ASSERT_EQ(e.solved.size(), 2u);
  EXPECT_FALSE(e.solved[0]);
  ASSERT_EQ(e.r.size(), 2 * 12 + 2 * 3u);
  for (std::size_t i = 0; i < 12; ++i)
    EXPECT_EQ(e.r[i], 0.0);
  // Tolerance ends with try_each: a normal evaluation throws again.
  EXPECT_THROW(ev(too_soft()), SolveError);
  // And the evaluator still solves a solvable case afterwards.
  const PointEvaluation ok = ev.try_each(fixtures::coarse_case());
  EXPECT_EQ(ok.solved, (std::vector<bool>{true, true}));
}

// On 2 ranks with --ranks-per-case 1, world rank 1 solves (and fails) the
// second posture: its solver message is logged there, by its group.
TEST(PointEvaluator, FailedPostureIsLoggedByTheGroupThatSolvedIt)
{
  const Recording rec = standing_and_supine();
  CaseGroups groups(MPI_COMM_WORLD, 1, "--ranks-per-case");
  std::ostringstream captured;
  const auto previous = spdlog::default_logger();
  spdlog::set_default_logger(std::make_shared<spdlog::logger>(
      "captured", std::make_shared<spdlog::sinks::ostream_sink_st>(captured)));
  PointEvaluator ev(rec, groups.comm(), &groups);
  const PointEvaluation e = ev.try_each(too_soft());
  spdlog::set_default_logger(previous);
  ASSERT_EQ(e.solved, (std::vector<bool>{false, false}));
  const std::string text = captured.str();
  for (std::size_t i = 0; i < rec.postures.size(); ++i)
  {
    const bool logged = text.find("posture '" + rec.postures[i].name + "' not solved") != std::string::npos;
    EXPECT_EQ(logged, groups.runs(i)) << text;
  }
}

TEST(PointEvaluator, LeaveOutFailuresExcludesOnlyNewFailures)
{
  const Recording rec = standing_and_supine();
  PointEvaluator ev(rec, MPI_COMM_WORLD);
  PointEvaluation e;
  EXPECT_TRUE(ev.leave_out_failures(fixtures::coarse_case(), e).empty());
  EXPECT_EQ(e.solved, (std::vector<bool>{true, true}));
  ev.exclude(1);
  EXPECT_EQ(ev.leave_out_failures(too_soft(), e), (std::vector<std::size_t>{0}));
  EXPECT_TRUE(ev.excluded(0));
  EXPECT_EQ(e.solved, (std::vector<bool>{false, false}));
  // Both left out now: nothing is solved, nothing newly lost.
  const int solves = ev.posture_solves();
  EXPECT_TRUE(ev.leave_out_failures(fixtures::coarse_case(), e).empty());
  EXPECT_EQ(ev.posture_solves(), solves);
}

TEST(PointEvaluator, UnsolvedPostureTakesTheLargestMeasuredFloor)
{
  std::vector<double> floor = {1e-4, 0.0, 3e-4, 0.0};
  EXPECT_TRUE(fill_unsolved(floor, {true, false, true, false}));
  EXPECT_EQ(floor, (std::vector<double>{1e-4, 3e-4, 3e-4, 3e-4}));
  std::vector<double> none = {0.0, 0.0};
  EXPECT_FALSE(fill_unsolved(none, {false, false}));
}

// Posture k held out: delta = -sum_{-k} J r / sum_{-k} J^2 (one parameter),
// the case at mu exp(delta) solved, chi2 over k's rows. A Jacobian of k's own
// rows 1000 times too large ruins the linearised prediction, not the solved one.
TEST(PointEvaluator, HeldOutPredictionSolvedDoesNotUseTheHeldOutPosturesJacobian)
{
  const Recording rec = standing_and_supine();
  const Config c = fixtures::coarse_case();
  PointEvaluator ev(rec, MPI_COMM_WORLD);
  const auto frees = frees_from_fit("mu", c);
  const FitState s = mu_fit(ev, c, frees, 0.05);
  const auto rows = rows_by_posture(s, rec);
  const auto solved = solved_held_out_chi2(ev, {c, frees, s}, rec);
  ASSERT_EQ(solved.size(), 2u);
  ASSERT_TRUE(solved[0] && solved[1]);
  EXPECT_FALSE(ev.excluded(0));
  EXPECT_FALSE(ev.excluded(1));

  double jr = 0, jj = 0;
  for (std::size_t i : rows[0])
  {
    jr += s.J[i][0] * s.r[i];
    jj += s.J[i][0] * s.J[i][0];
  }
  ASSERT_GT(std::abs(jr / jj), 1e-3); // the step is not trivially zero
  const auto e = ev(config_at(c, frees, {std::log(s.values[0]) - jr / jj}));
  double by_hand = 0;
  for (std::size_t i : rows[1])
    by_hand += e.r[i] * e.r[i];
  EXPECT_NEAR(*solved[1], by_hand, 1e-6 * by_hand);

  FitState broken = s;
  for (std::size_t i : rows[1])
    broken.J[i][0] *= 1000;
  EXPECT_GT(held_out_chi2(broken, rec)[1], 10 * *solved[1]);
  EXPECT_NEAR(*solved_held_out_chi2(ev, {c, frees, broken}, rec)[1], *solved[1], 1e-6 * *solved[1]);
  // A posture the evaluator leaves out is not solved, and stays left out.
  ev.exclude(0);
  const auto without_0 = solved_held_out_chi2(ev, {c, frees, s}, rec);
  EXPECT_FALSE(without_0[0]);
  EXPECT_NEAR(*without_0[1], *solved[1], 1e-6 * *solved[1]);
  EXPECT_TRUE(ev.excluded(0));
  EXPECT_FALSE(ev.excluded(1));
}

// A gain is solved only where both fits were solved: never a solved chi2
// against a linearised one.
TEST(PointEvaluator, SolvedGainsNeverMixSolvedAndLinearised)
{
  Evidence e;
  e.held_out_gain = {5.0, -7.0, 3.0};
  set_solved_gains({100.0, 80.0, std::nullopt}, {90.0, std::nullopt, 50.0}, e);
  EXPECT_TRUE(e.held_out_solved);
  EXPECT_EQ(e.held_out_gain, (std::vector<double>{10.0, -7.0, 3.0}));
  EXPECT_EQ(e.held_out_gain_linearised, (std::vector<double>{5.0, -7.0, 3.0}));
}

// y + delta within the bounds, in ln p: ln 2 + 10 stops at ln 30 (hi), the
// second parameter moves freely, a third without a step stays.
TEST(FitState, StepWithinBoundsClampsToTheFreesBounds)
{
  std::vector<Free> frees(3);
  frees[0].lo = 1, frees[0].hi = 30;
  frees[1].lo = 1e-3, frees[1].hi = 1e3;
  frees[2].lo = 1, frees[2].hi = 10;
  const auto y = step_within_bounds({std::log(2.0), 0.0, std::log(5.0)}, {10.0, -0.5}, frees);
  ASSERT_EQ(y.size(), 3u);
  EXPECT_NEAR(y[0], std::log(30.0), 1e-15);
  EXPECT_NEAR(y[1], -0.5, 1e-15);
  EXPECT_NEAR(y[2], std::log(5.0), 1e-15);
}
