// SPDX-License-Identifier: LGPL-3.0-or-later
// Mesh convergence of the default case's standing nipple displacement under
// uniform refinement (gmsh splitting, boundary nodes snapped to the sphere):
// the value settles and the observed order is recorded (printed; see
// docs/VERIFICATION.md). The observed order is low (~0.5 for P1 on these
// coarse meshes, ~1.2 for P2): the skin membrane ends at the base rim and
// loads the body there like a line force, a singularity that pollutes the
// convergence of every observable.
#include "fixtures.hpp"
#include <gtest/gtest.h>

using namespace breastsim;

TEST(Convergence, StandingNippleDisplacementSettles)
{
  std::vector<double> dz, cells;
  for (int level = 0; level < 3; ++level)
  {
    Config c = fixtures::coarse_case(1, 0.02);
    c.set("geometry.refinements", std::int64_t(level));
    auto m = fixtures::make_model(c);
    NewtonSolver newton(*m, NewtonOptions::from(c));
    ObservableProbe probe(*m, {0, c.number("geometry.H"), 0});
    auto r = solve_posture(*m, newton, probe, named_posture("standing"), c);
    dz.push_back(r.observables.nipple[2]);
    cells.push_back(m->mesh().mesh->topology().index_map(3)->size_global());
  }
  const double d1 = std::abs(dz[1] - dz[0]), d2 = std::abs(dz[2] - dz[1]);
  const double order = std::log2(d1 / d2);
  const double richardson = dz[2] + (dz[2] - dz[1]) / (std::pow(2.0, order) - 1);
  std::printf("nipple z displacement [mm] by level (cells): %.4f (%g), %.4f (%g), %.4f (%g); "
              "observed order %.2f; Richardson %.4f mm\n",
              1e3 * dz[0], cells[0], 1e3 * dz[1], cells[1], 1e3 * dz[2], cells[2], order,
              1e3 * richardson);
  EXPECT_LT(d2, 0.8 * d1);                                   // the increments shrink
  EXPECT_LT(std::abs(dz[2] - richardson), 0.15 * std::abs(dz[2])); // and settle
}
