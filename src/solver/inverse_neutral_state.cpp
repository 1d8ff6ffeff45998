// SPDX-License-Identifier: LGPL-3.0-or-later
#include "inverse_neutral_state.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "reference_reset.hpp"
#include "timer.hpp"
#include "warm_start.hpp"
#include <algorithm>
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <fmt/format.h>
#include <mpi.h>

namespace breastsim
{
namespace
{
/// The inverse problem's state on this rank: the target shape and the node
/// to displacement-dof map, over the local geometry nodes (owned first).
struct InverseState
{
  std::vector<double> target;      ///< x_s, (nodes, 3)
  std::vector<std::int32_t> block; ///< u dof block of each node
  std::int32_t owned = 0;          ///< geometry nodes owned by this rank
  MPI_Comm comm;
  std::vector<char> frozen;        ///< (nodes, 3): component neither updated nor measured
};

/// The y components of the nodes on the chest plane y = 0 of the target.
std::vector<char> chest_plane_components(const std::vector<double>& target)
{
  double extent = 0;
  for (double v : target)
    extent = std::max(extent, std::abs(v));
  std::vector<char> frozen(target.size(), 0);
  for (std::size_t n = 0; 3 * n < target.size(); ++n)
    frozen[3 * n + 1] = std::abs(target[3 * n + 1]) <= 1e-9 * extent;
  return frozen;
}

/// r = x_s - X - u at every local node.
std::vector<double> mismatch(const Model& model, const InverseState& s)
{
  const std::span<const double> x = model.mesh().mesh->geometry().x();
  const auto u = model.displacement()->x()->array();
  std::vector<double> r(s.target.size(), 0.0);
  for (std::size_t n = 0; n < s.block.size(); ++n)
    for (int k = 0; k < 3 && s.block[n] >= 0; ++k)
      if (!s.frozen[3 * n + k])
        r[3 * n + k] = s.target[3 * n + k] - x[3 * n + k] - u[3 * s.block[n] + k];
  return r;
}

/// Sum over the owned nodes of a . b (collective).
double dot(const std::vector<double>& a, const std::vector<double>& b, const InverseState& s)
{
  double local = 0, global = 0;
  for (std::size_t i = 0; i < 3 * static_cast<std::size_t>(s.owned); ++i)
    local += a[i] * b[i];
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, s.comm);
  return global;
}

/// RMS and max of the node mismatch |r_n| (collective).
std::pair<double, double> mismatch_size(const std::vector<double>& r, const InverseState& s)
{
  double local_max = 0, global_max = 0;
  for (std::int32_t n = 0; n < s.owned; ++n)
    local_max = std::max(local_max, std::hypot(r[3 * n], r[3 * n + 1], r[3 * n + 2]));
  MPI_Allreduce(&local_max, &global_max, 1, MPI_DOUBLE, MPI_MAX, s.comm);
  double count = s.owned, total = 0;
  MPI_Allreduce(&count, &total, 1, MPI_DOUBLE, MPI_SUM, s.comm);
  return {std::sqrt(dot(r, r, s) / std::max(total, 1.0)), global_max};
}

/// The forward solve from the model's current reference, starting from the
/// last u; throws SolveError naming the iteration.
int forward_solve(Model& model, NewtonSolver& newton, const InverseOptions& o, double reference_norm,
                  int iteration)
{
  const Guess last{[](Model&, std::string&) { return true; }, "the last iteration's u", true};
  const WarmStartReport w
      = solve_at_full_load(model, newton, last, o.ramp,
                           fmt::format("inverse neutral state, iteration {}", iteration), reference_norm);
  return w.path.newton_iterations;
}
} // namespace

InverseReport inverse_neutral_state(Model& model, NewtonSolver& newton, const InverseOptions& o,
                                    double reference_norm)
{
  const Stopwatch stopwatch("inverse neutral state");
  auto mesh = model.mesh().mesh;
  std::span<double> x = mesh->geometry().x();
  InverseState s{{x.begin(), x.end()}, node_dof_blocks(model),
                 mesh->geometry().index_map()->size_local(), mesh->comm(), {}};
  s.frozen = o.keep_chest_plane ? chest_plane_components(s.target) : std::vector<char>(s.target.size(), 0);
  InverseReport report;
  std::vector<double> r_prev;
  double omega = 1.0;
  int growing = 0;
  for (int k = 0; k < o.max_iterations; ++k)
  {
    InverseIteration it;
    it.newton_iterations = forward_solve(model, newton, o, reference_norm, k);
    const std::vector<double> r = mismatch(model, s);
    std::tie(it.rms_mismatch, it.max_mismatch) = mismatch_size(r, s);
    log::info("inverse neutral state {}: mismatch RMS {:.3g} mm, max {:.3g} mm", k,
              1e3 * it.rms_mismatch, 1e3 * it.max_mismatch);
    growing = !report.iterations.empty() && it.max_mismatch > report.iterations.back().max_mismatch
                  ? growing + 1 : 0;
    if (it.max_mismatch <= o.tolerance)
    {
      report.iterations.push_back(it);
      report.converged = true;
      break;
    }
    if (growing >= 3)
      throw SolveError(fmt::format("inverse neutral state: the mismatch grew for 3 iterations (to {:.3g} mm "
                                   "at iteration {}): the material cannot hold this shape under the load",
                                   1e3 * it.max_mismatch, k));
    // Aitken: omega_k = -omega_{k-1} r_{k-1}.(r_k - r_{k-1}) / |r_k - r_{k-1}|^2
    if (!r_prev.empty())
    {
      std::vector<double> dr(r.size());
      for (std::size_t i = 0; i < r.size(); ++i)
        dr[i] = r[i] - r_prev[i];
      const double den = dot(dr, dr, s);
      if (den > 0)
        omega = std::clamp(-omega * dot(r_prev, dr, s) / den, 0.05, 2.0);
    }
    it.omega = omega;
    for (std::size_t i = 0; i < r.size(); ++i)
      x[i] += omega * r[i];
    r_prev = r;
    report.iterations.push_back(it);
  }
  report.seconds = stopwatch.seconds();
  if (!report.converged)
    throw SolveError(fmt::format("inverse neutral state: the mismatch is {:.3g} mm after {} iterations, above "
                                 "the tolerance {:.3g} mm",
                                 1e3 * report.iterations.back().max_mismatch, o.max_iterations,
                                 1e3 * o.tolerance));
  return report;
}
} // namespace breastsim
