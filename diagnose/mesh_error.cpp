// SPDX-License-Identifier: LGPL-3.0-or-later
#include "mesh_error.hpp"
#include "geometry_options.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "point_neighbours.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace breastsim::diagnosis
{
Config finer(const Config& c, double ratio)
{
  Config f = c;
  f.set("geometry.mesh_size", HalfCapSpec::from(c).mesh_size / ratio);
  f.validate();
  return f;
}

namespace
{
/// Element-wise change b_i - a_i of two distance lists [m].
std::vector<double> difference(const std::vector<double>& a, const std::vector<double>& b)
{
  std::vector<double> c;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
    c.push_back(b[i] - a[i]);
  return c;
}

/// RMS of a list of changes [m] (0 for an empty list).
double rms(const std::vector<double>& c)
{
  double ss = 0;
  for (double x : c)
    ss += x * x;
  return std::sqrt(ss / std::max<std::size_t>(c.size(), 1));
}

/// RMS change of a landmark over its three components [m].
double landmark_change(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return rms(difference({a[0], a[1], a[2]}, {b[0], b[1], b[2]}));
}
} // namespace

std::vector<double> local_floor(const std::vector<Point>& pts, const std::vector<double>& change,
                                int k)
{
  k = std::min<int>(k, static_cast<int>(pts.size()) - 1);
  return neighbourhood_rms(change, nearest_neighbours(pts, std::max(k, 0)));
}

bool fill_unsolved(std::vector<double>& floor, const std::vector<bool>& solved)
{
  double largest = -1;
  for (std::size_t p = 0; p < floor.size(); ++p)
    if (solved[p])
      largest = std::max(largest, floor[p]);
  for (std::size_t p = 0; p < floor.size(); ++p)
    if (!solved[p])
      floor[p] = std::max(largest, 0.0);
  return largest >= 0;
}

namespace
{
/// sigma_eff of each point of posture p: from its own e_h,i (local floor of
/// a solved posture) or, unsolved on the finer mesh, from the posture's e_h.
void append_point_sigmas(std::vector<double>& sigma, const Recording& rec, std::size_t p,
                         const std::vector<double>& change, const DiagnoseOptions& o, Diagnosis& d)
{
  const auto& pts = rec.postures[p].points;
  if (change.empty())
  {
    sigma.insert(sigma.end(), pts.size(), d.sigma_eff[p]);
    return;
  }
  const auto e = local_floor(pts, change, o.neighbours);
  for (double e_i : e)
    sigma.push_back(std::hypot(rec.noise_sigma, e_i)); // sigma_eff,i^2 = sigma^2 + e_h,i^2
  d.local_floor_max[p] = *std::max_element(e.begin(), e.end());
}
} // namespace

std::vector<double> noise_floor(PointEvaluator& ev, PointEvaluator& fine_ev, const Recording& rec,
                                const FitState& state, const DiagnoseOptions& o, Diagnosis& d)
{
  log::info("numerical noise floor: solving the fitted model on a mesh {:g} times finer", o.mesh_ratio);
  const PointEvaluation ef = fine_ev.try_each(finer(state.config, o.mesh_ratio));
  const PointEvaluation ec = ev(state.config);
  const std::size_t np = rec.postures.size();
  std::vector<double> landmark_error(np, 0.0);
  std::vector<bool> landmark_solved(np, false);
  std::vector<std::vector<double>> change(np); // d_{h/r},i - d_h,i of the solved postures
  for (std::size_t p = 0; p < np; ++p)
    if (ef.solved[p])
    {
      change[p] = difference(ec.distances[p], ef.distances[p]);
      d.mesh_error[p] = rms(change[p]);
      landmark_solved[p] = rec.postures[p].nipple.has_value();
      if (landmark_solved[p])
        landmark_error[p] = landmark_change(ef.nipple_error[p], ec.nipple_error[p]);
    }
  if (!fill_unsolved(d.mesh_error, ef.solved))
    throw SolveError(fmt::format("the fitted current model cannot be solved on the mesh {:g} times "
                                 "finer in any posture, so it has no numerical noise floor "
                                 "(--mesh-ratio 1 turns the floor off)", o.mesh_ratio));
  fill_unsolved(landmark_error, landmark_solved);
  for (std::size_t p = 0; p < np; ++p)
    if (!ef.solved[p])
    {
      fine_ev.exclude(p); // no refinement check can use it
      d.unsolved_on_finer.push_back(rec.postures[p].name);
      log::warn("posture '{}': the fitted model cannot be solved on the finer mesh; its numerical "
                "noise floor is the largest of the other postures', and the refinement checks "
                "leave it out", rec.postures[p].name);
    }
  std::vector<double> sigma;
  d.local_floor_max = d.mesh_error; // an unsolved posture's points keep the posture's floor
  for (std::size_t p = 0; p < np; ++p)
  {
    d.sigma_eff[p] = std::hypot(rec.noise_sigma, d.mesh_error[p]);
    append_point_sigmas(sigma, rec, p, change[p], o, d);
    log::info("numerical noise floor of posture '{}': {:.3f} mm (sigma_eff {:.3f} mm)",
              rec.postures[p].name, 1e3 * d.mesh_error[p], 1e3 * d.sigma_eff[p]);
  }
  for (std::size_t p = 0; p < np; ++p)
    if (rec.postures[p].nipple)
      sigma.insert(sigma.end(), 3, std::hypot(rec.noise_sigma, landmark_error[p]));
  return sigma;
}

FitState with_numerical_uncertainty(const FitState& coarse, const FitState& fine, double ratio,
                                    bool values_from_fine, std::vector<double>& se_numerical)
{
  FitState f = values_from_fine ? fine : coarse;
  f.config.set("geometry.mesh_size", HalfCapSpec::from(coarse.config).mesh_size); // the user's mesh
  auto& u = f.uncertainty;
  for (std::size_t i = 0; i < f.values.size() && i < u.se_log.size() && i < fine.values.size(); ++i)
  {
    const double se_num = std::abs(std::log(fine.values[i] / coarse.values[i])) / (ratio - 1);
    se_numerical.push_back(se_num);
    widen_interval(u, i, f.values[i], se_num);
  }
  return f;
}
} // namespace breastsim::diagnosis
