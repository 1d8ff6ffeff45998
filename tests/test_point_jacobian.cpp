// SPDX-License-Identifier: LGPL-3.0-or-later
// The diagnosis' exact Jacobian (fit_jacobian: the point distances' and
// landmarks' derivatives along du/dy from one linear solve per parameter)
// against central differences of the nonlinear solves, for the fittable
// material parameters and every candidate's q, at P1 and P2 in two
// postures. A recorded point whose closest triangle changes within the
// difference step has a distance that jumps (the normal of another
// triangle): such rows, where the central difference disagrees with both
// one-sided differences, are not compared, and there are few. Serial and on
// 2 ranks (ctest unit_mpi_sensitivities).
#include "candidates.hpp"
#include "fit_state.hpp"
#include "fixtures.hpp"
#include "point_evaluator.hpp"
#include "recording.hpp"
#include "recording_generator.hpp"
#include <gtest/gtest.h>
#include <iostream>

using namespace breastsim;
using namespace breastsim::diagnosis;

namespace
{
/// A synthetic recording of `c` (points made on rank 0) on every rank.
calibration::Recording recording(const Config& c, int points)
{
  RecordingOptions ro;
  ro.points = points;
  ro.mesh_size = 0.016;
  std::string text = calibration::to_json(synthetic_recording(c, ro, MPI_COMM_WORLD)).dump();
  int n = static_cast<int>(text.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, MPI_COMM_WORLD);
  text.resize(n);
  MPI_Bcast(text.data(), n, MPI_CHAR, 0, MPI_COMM_WORLD);
  return calibration::parse_recording(nlohmann::json::parse(text), "test");
}

struct Column
{
  double worst = 0;     ///< largest |exact - central| / the column's largest |entry|
  int kinks = 0;        ///< rows not compared (their closest triangle changed)
  std::size_t rows = 0;
};

/// Compare column j of `J` with central differences of step h in y_j. A
/// row that differs by more than 1e-5 of the column's scale is compared
/// again with the step h / 10: the distance to the skin is C1 but not C2
/// where the closest point moves from a triangle onto an edge, and a
/// stencil that straddles such a place errs by O(h); an exact column agrees
/// at one of the two steps, a wrong one at neither.
Column compare(PointEvaluator& ev, const Config& base, const std::vector<Free>& frees,
               const std::vector<double>& y, const Matrix& J, std::size_t j)
{
  const double h = 1e-4;
  auto at = [&](double step)
  {
    auto yy = y;
    yy[j] += step;
    return ev(config_at(base, frees, yy)).r;
  };
  const auto r0 = at(0), rp = at(h), rm = at(-h);
  Column col;
  col.rows = r0.size();
  double scale = 0;
  for (std::size_t i = 0; i < r0.size(); ++i)
    scale = std::max(scale, std::abs(J[i][j]));
  EXPECT_GT(scale, 0.0) << frees[j].name << " moves nothing";
  std::vector<std::size_t> again;
  for (std::size_t i = 0; i < r0.size(); ++i)
  {
    const double central = (rp[i] - rm[i]) / (2 * h), forward = (rp[i] - r0[i]) / h,
                 backward = (r0[i] - rm[i]) / h;
    if (std::abs(forward - backward) > 1e-3 * scale) // a jump within the step
    {
      ++col.kinks;
      continue;
    }
    const double error = std::abs(J[i][j] - central) / scale;
    if (error > 1e-5)
      again.push_back(i);
    else
      col.worst = std::max(col.worst, error);
  }
  int any = again.empty() ? 0 : 1; // the solves below are collective
  MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (!any)
    return col;
  const auto rp2 = at(h / 10), rm2 = at(-h / 10);
  for (std::size_t i : again)
    col.worst = std::max(col.worst, std::min(std::abs(J[i][j] - (rp[i] - rm[i]) / (2 * h)),
                                             std::abs(J[i][j] - (rp2[i] - rm2[i]) / (h / 5))) / scale);
  return col;
}

Config tight(Config c)
{
  c.set("solver.rtol", 1e-12);
  c.set("solver.atol", 1e-14);
  c.set("solver.inexact_newton", false);
  c.set("postures.names", std::vector<std::string>{"standing", "supine"});
  c.validate();
  return c;
}
} // namespace

class PointJacobian : public ::testing::TestWithParam<int>
{
};

TEST_P(PointJacobian, MatchesCentralDifferencesOfTheNonlinearSolves)
{
  const int order = GetParam();
  const Config c = tight(fixtures::coarse_case(order, 0.016));
  const auto rec = recording(c, 150);
  PointEvaluator ev(rec, MPI_COMM_WORLD);

  // The material parameters, then each candidate's q (with its term on).
  std::vector<std::pair<Config, std::vector<Free>>> fits = {{c, frees_from_fit("mu,lambda,mu_s,c", c)}};
  for (const auto& cand : candidate_library())
    if (cand.applicable(c))
      fits.push_back({c, {free_candidate(cand)}});
  double worst = 0;
  int kinks = 0;
  std::size_t rows = 0;
  for (const auto& [base, frees] : fits)
  {
    const auto y = start_values(frees);
    const auto r = ev(config_at(base, frees, y)).r;
    int evaluations = 0;
    const Matrix J = fit_jacobian(ev, base, frees, y, r, 1e-3, evaluations);
    EXPECT_EQ(evaluations, 0) << "every column exact";
    for (std::size_t j = 0; j < frees.size(); ++j)
    {
      const Column col = compare(ev, base, frees, y, J, j);
      EXPECT_LT(col.worst, 1e-5) << "P" << order << ", d r / d ln " << frees[j].name;
      EXPECT_LT(col.kinks, static_cast<int>(col.rows / 20)) << frees[j].name;
      worst = std::max(worst, col.worst);
      kinks += col.kinks;
      rows += col.rows;
    }
  }
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0)
    std::cout << "P" << order << ": largest |exact - central| / column scale = " << worst << ", "
              << kinks << " of " << rows << " rows with a triangle change not compared\n";
}

TEST(PointJacobian, NeutralShapeKeepsForwardDifferences)
{
  const Config c = tight(fixtures::coarse_case(1, 0.016));
  const auto rec = recording(c, 60);
  PointEvaluator ev(rec, MPI_COMM_WORLD);
  const auto frees = frees_from_fit("mu,R", c);
  const auto y = start_values(frees);
  const auto r = ev(config_at(c, frees, y)).r;
  int evaluations = 0;
  const Matrix J = fit_jacobian(ev, c, frees, y, r, 1e-3, evaluations);
  EXPECT_EQ(evaluations, 1); // the R column
  const Column col = compare(ev, c, frees, y, J, 0);
  EXPECT_LT(col.worst, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Orders, PointJacobian, ::testing::Values(1, 2),
                         [](const auto& info) { return "P" + std::to_string(info.param); });
