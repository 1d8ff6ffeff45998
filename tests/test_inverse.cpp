// SPDX-License-Identifier: LGPL-3.0-or-later
// The stress-free neutral state by inverse elastostatics
// (src/solver/inverse_neutral_state.hpp): a round trip from a known
// reference to its loaded shape and back.
#include "errors.hpp"
#include "fixtures.hpp"
#include "inverse_neutral_state.hpp"
#include "model_setup.hpp"
#include "posture.hpp"
#include "reference_reset.hpp"
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <gtest/gtest.h>

using namespace breastsim;

namespace
{
/// RMS and max over the owned geometry nodes of |a - b| (collective).
std::pair<double, double> node_distance(const Model& m, const std::vector<double>& a,
                                        const std::vector<double>& b)
{
  const std::int32_t owned = m.mesh().mesh->geometry().index_map()->size_local();
  double ss = 0, mx = 0, n = owned;
  for (std::int32_t i = 0; i < owned; ++i)
  {
    const double d = std::hypot(a[3 * i] - b[3 * i], a[3 * i + 1] - b[3 * i + 1], a[3 * i + 2] - b[3 * i + 2]);
    ss += d * d;
    mx = std::max(mx, d);
  }
  double g[3] = {ss, n, mx}, out[3];
  MPI_Allreduce(g, out, 2, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&g[2], &out[2], 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return {std::sqrt(out[0] / out[1]), out[2]};
}

std::vector<double> geometry(const Model& m)
{
  const auto x = m.mesh().mesh->geometry().x();
  return {x.begin(), x.end()};
}

/// The default case's half cap (coarse) loaded standing: the model holds
/// the loaded shape as its reference; returns the true reference.
std::vector<double> load_the_cap(Model& m, const Config& c)
{
  apply_parameters(c, m);
  fixtures::solve_gravity(m, gravity_vector(0.0, 9.81));
  const std::vector<double> reference = geometry(m);
  reset_reference(m); // the loaded shape becomes the mesh, u = 0
  return reference;
}
} // namespace

// Forward from the cap to standing, then inverse: the reference is
// recovered within 0.5 mm RMS and the loaded shape reproduced within 0.1 mm.
TEST(InverseNeutralState, RoundTripOnTheCap)
{
  const Config c = fixtures::coarse_case();
  auto m = fixtures::make_model(c);
  const std::vector<double> reference = load_the_cap(*m, c);
  const std::vector<double> loaded = geometry(*m);
  const auto [sag_rms, sag_max] = node_distance(*m, loaded, reference);
  ASSERT_GT(sag_max, 5e-3) << "the load must move the cap noticeably";

  NewtonSolver newton(*m, NewtonOptions{});
  const double f = set_gravity(*m, gravity_vector(0.0, 9.81));
  InverseOptions o;
  o.tolerance = 1e-6;
  const InverseReport r = inverse_neutral_state(*m, newton, o, f);
  ASSERT_TRUE(r.converged);
  EXPECT_LE(r.iterations.back().max_mismatch, 1e-6);
  const auto [rms, max] = node_distance(*m, geometry(*m), reference);
  EXPECT_LT(rms, 0.5e-3) << "iterations " << r.iterations.size();
  EXPECT_LT(max, 1e-5) << "the fixed point is unique on this mesh: X is recovered to the tolerance's order";
  std::printf("inverse neutral state: %zu iterations, %.1f s; sag max %.2f mm; reference "
              "recovered to RMS %.4f mm, max %.4f mm\n",
              r.iterations.size(), r.seconds, 1e3 * sag_max, 1e3 * rms, 1e3 * max);
}

TEST(InverseNeutralState, NamesTheIterationsWhenItDoesNotConverge)
{
  const Config c = fixtures::coarse_case();
  auto m = fixtures::make_model(c);
  load_the_cap(*m, c);
  NewtonSolver newton(*m, NewtonOptions{});
  const double f = set_gravity(*m, gravity_vector(0.0, 9.81));
  InverseOptions o;
  o.max_iterations = 1;
  o.tolerance = 1e-9;
  try
  {
    inverse_neutral_state(*m, newton, o, f);
    FAIL() << "one iteration reached 1e-9 m";
  }
  catch (const SolveError& e)
  {
    EXPECT_NE(std::string(e.what()).find("after 1 iterations"), std::string::npos) << e.what();
  }
}
