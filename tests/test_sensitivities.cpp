// SPDX-License-Identifier: LGPL-3.0-or-later
// Exact sensitivities of the calibration's forward model
// (ForwardModel::sensitivities: one linear solve with the tangent at the
// equilibrium, K du/dp = -dR/dp) against central differences of the full
// nonlinear solve, for every fittable material parameter of every term
// (the registry's --fit names; R, H keep forward differences), at P1 and
// P2 on a coarse mesh in two postures. The Newton tolerance is tight and the
// step (1e-3 relative) small enough that the central difference itself is
// accurate to ~1e-6 of the column. Also run on 2 ranks (tests/CMakeLists.txt).
#include "breastsim_registry.hpp"
#include "forward_model.hpp"
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>

using namespace breastsim;

namespace
{
/// The observables a measurement can name (calibrate/inputs/measurements.hpp).
std::vector<double> measurable(const Observables& o)
{
  return {o.nipple[0], o.nipple[1], o.nipple[2], o.projection, o.z_min, o.z_max, o.base_perimeter};
}

const char* const observable_names[] = {"nipple_x", "nipple_y", "nipple_z", "projection",
                                        "z_min",    "z_max",    "base_perimeter"};
} // namespace

class Sensitivities : public ::testing::TestWithParam<int>
{
};

TEST_P(Sensitivities, MatchCentralDifferencesOfTheNonlinearSolve)
{
  const int order = GetParam();
  Config c;
  c.set("geometry.mesh_size", 0.012);
  c.set("geometry.order", std::int64_t(order));
  c.set("postures.names", std::vector<std::string>{"standing", "supine"});
  c.set("solver.rtol", 1e-12);          // relative to the gravity load (~2 N)
  c.set("solver.atol", 1e-14);
  c.set("solver.inexact_newton", false); // every Newton step solved exactly
  std::vector<std::string> keys;
  for (const auto& a : generated::fit_aliases())
    if (a.role != generated::FitRole::shape)
    {
      keys.push_back(a.key);
      c.set("terms." + a.term, true); // the parameter's term on
    }
  c.validate();
  ASSERT_GE(keys.size(), 6u); // mu, lambda, mu_s, lambda_s, c, rho

  const std::vector<Posture> postures = {named_posture("standing"), named_posture("supine")};
  calibration::ForwardModel fm(postures, MPI_COMM_WORLD);
  fm.solve(c);
  std::vector<std::vector<Observables>> exact; // [posture][key]
  for (std::size_t i = 0; i < postures.size(); ++i)
    exact.push_back(fm.sensitivities(i, c, keys));

  const double h = 1e-3; // relative step of the central difference
  double worst = 0;      // largest error relative to its column's scale
  for (std::size_t j = 0; j < keys.size(); ++j)
  {
    const double p = c.number(keys[j]);
    auto solve_at = [&](double factor)
    {
      Config k = c;
      k.set(keys[j], p * factor);
      k.validate();
      return fm.solve(k);
    };
    const auto plus = solve_at(1 + h), minus = solve_at(1 - h);
    for (std::size_t i = 0; i < postures.size(); ++i)
    {
      const auto gp = measurable(plus[i]), gm = measurable(minus[i]), ge = measurable(exact[i][j]);
      std::vector<double> fd;
      double scale = 0; // the column's largest |dG/d ln p|
      for (std::size_t k = 0; k < gp.size(); ++k)
      {
        fd.push_back((gp[k] - gm[k]) / (2 * h * p));
        scale = std::max(scale, std::abs(fd.back()) * p);
      }
      ASSERT_GT(scale, 1e-6) << keys[j] << " moves no observable in " << postures[i].name;
      for (std::size_t k = 0; k < gp.size(); ++k)
        worst = std::max(worst, std::abs(ge[k] - fd[k]) * p / scale);
      for (std::size_t k = 0; k < gp.size(); ++k)
        EXPECT_LT(std::abs(ge[k] - fd[k]) * p, 1e-5 * scale)
            << "P" << order << ", " << postures[i].name << ", d " << observable_names[k] << " / d "
            << keys[j] << ": exact " << ge[k] << ", central difference " << fd[k];
    }
  }
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0)
    std::cout << "P" << order << ": largest |exact - central difference| / column scale = " << worst
              << " (" << keys.size() << " parameters)\n";
}

INSTANTIATE_TEST_SUITE_P(Orders, Sensitivities, ::testing::Values(1, 2),
                         [](const auto& info) { return "P" + std::to_string(info.param); });
