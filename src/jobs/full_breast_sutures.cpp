// SPDX-License-Identifier: LGPL-3.0-or-later
#include "full_breast_sutures.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "partner_field.hpp"
#include "timer.hpp"
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace breastsim
{
void set_mirror_map(Model& model)
{
  model.set_parameter("tissue_map_matrix", {-1, 0, 0, 0, 1, 0, 0, 0, 1});
  model.set_parameter("tissue_map_shift", {0, 0, 0});
}

double max_tissue_suture_gap(Model& model)
{
  const auto& w = model.partner("tissue_suture").field()->x()->array(); // w = P u, updated
  const auto u = model.displacement()->x()->array();
  const auto X = model.space()->tabulate_dof_coordinates(false);
  const auto G = model.parameter("tissue_map_matrix"), t = model.parameter("tissue_map_shift");
  double gap = 0;
  for (auto n : model.boundary_nodes("suture_a"))
  {
    double d2 = 0;
    for (int r = 0; r < 3; ++r)
    {
      // f(X) - f(g(X)) = X + u - (G X + t) - w
      const double gX = G[3 * r] * X[3 * n] + G[3 * r + 1] * X[3 * n + 1] + G[3 * r + 2] * X[3 * n + 2] + t[r];
      const double d = X[3 * n + r] + u[3 * n + r] - gX - w[3 * n + r];
      d2 += d * d;
    }
    gap = std::max(gap, std::sqrt(d2));
  }
  double global = 0;
  MPI_Allreduce(&gap, &global, 1, MPI_DOUBLE, MPI_MAX, model.mesh().mesh->comm());
  return global;
}

namespace
{
/// Both gaps into `rep`.
void measure_gaps(Model& model, FullSutureReport& rep)
{
  rep.gap_tissue = max_tissue_suture_gap(model);
  rep.gap_chest = max_suture_gap(model);
  rep.suture.max_gap = std::max(rep.gap_tissue, rep.gap_chest);
}

/// Both closures 0 -> 1, then both penalties x10 until the gap is at most surgery.max_gap.
void close_and_tighten_both(Model& model, const Config& c, FullSutureReport& rep)
{
  NewtonSolver newton(model, NewtonOptions::from(c));
  // Force scale: the two sutures' pull at the start of closure.
  model.set_parameter("closure", {1.0});
  model.set_parameter("tissue_closure", {1.0});
  const double f_ref = std::hypot(model.residual_norm("sutures"), model.residual_norm("tissue_suture"));
  LoadStepOptions opt = LoadStepOptions::from(c);
  opt.initial_step = std::min(opt.initial_step, 0.25);
  rep.suture.closure = continuation(model, newton, {{"closure", 0.0, 1.0}, {"tissue_closure", 0.0, 1.0}}, opt,
                                    "suture closure", f_ref);
  double k = model.parameter("k_suture")[0], kt = model.parameter("k_tissue_suture")[0];
  measure_gaps(model, rep);
  const double tol = SurgeryOptions::from(c).max_gap;
  while (rep.suture.max_gap > tol)
  {
    if (++rep.suture.penalty_raises > 6)
      throw SolveError(fmt::format("suture gap {:.3g} m (keel faces {:.3g} m, chest {:.3g} m) still above "
                                   "surgery.max_gap = {:.3g} m after raising the penalties to {:.3g} and {:.3g} Pa/m",
                                   rep.suture.max_gap, rep.gap_tissue, rep.gap_chest, tol, k, kt));
    rep.suture.closure.append(continuation(model, newton, {{"k_suture", k, 10 * k}, {"k_tissue_suture", kt, 10 * kt}},
                                           opt, "suture penalty", f_ref));
    k *= 10;
    kt *= 10;
    measure_gaps(model, rep);
    log::info("suture penalties raised to {:.3g} (chest) and {:.3g} Pa/m (keel): largest gaps {:.4f} mm (chest), "
              "{:.4f} mm (keel)", k, kt, 1e3 * rep.gap_chest, 1e3 * rep.gap_tissue);
  }
  rep.suture.k_final = k;
}

/// The fold site and the nearest named point, for a failed closure.
std::string describe_fold(Model& model, const std::vector<std::pair<std::string, std::array<double, 3>>>& points)
{
  const FoldSite f = fold_site(model);
  std::string s = fmt::format("; in the last converged state the smallest det F at a check point is {:.3g}, in "
                              "the tetrahedron centred at ({:.1f}, {:.1f}, {:.1f}) mm",
                              f.det_min, 1e3 * f.x[0], 1e3 * f.x[1], 1e3 * f.x[2]);
  double best = std::numeric_limits<double>::infinity();
  std::string name;
  for (const auto& [n, p] : points)
    if (const double d = std::hypot(p[0] - f.x[0], p[1] - f.x[1], p[2] - f.x[2]); d < best)
      best = d, name = n;
  return points.empty() ? s : s + fmt::format(", {:.1f} mm from incision point {}", 1e3 * best, name);
}
} // namespace

FullSutureReport close_full_breast_sutures(Model& model, const Config& c,
                                           const std::vector<std::pair<std::string, std::array<double, 3>>>& points)
{
  Stopwatch clock("surgery: sutures");
  FullSutureReport rep;
  const bool gravity_on = model.term_on("gravity");
  set_mirror_map(model);
  model.set_term("sutures", true);
  model.set_term("tissue_suture", true);
  model.set_term("gravity", false); // knitting happens in the neutral (gravity-free) state
  try
  {
    close_and_tighten_both(model, c, rep);
  }
  catch (const SolveError& e)
  {
    throw SolveError(e.what() + describe_fold(model, points));
  }
  model.set_term("gravity", gravity_on);
  rep.images = model.partner("tissue_suture").image_stats();
  rep.suture.seconds = clock.seconds();
  return rep;
}
} // namespace breastsim
