// SPDX-License-Identifier: LGPL-3.0-or-later
#include "recording_generator.hpp"
#include "case_options.hpp"
#include "candidates.hpp"
#include "errors.hpp"
#include "fit_parameters.hpp"
#include "log.hpp"
#include "model_setup.hpp"
#include "neutral_mesh.hpp"
#include "posture_solve.hpp"
#include "surface_export.hpp"
#include <cmath>
#include <fmt/format.h>
#include <random>

namespace breastsim::diagnosis
{
namespace
{
/// n points uniform in area on the deformed surface, each with noise.
std::vector<calibration::Point> sample_surface(const SkinSurface& s, int n, double sigma, std::mt19937& gen)
{
  std::vector<double> cumulative;
  double total = 0;
  for (const auto& t : s.triangles)
  {
    const auto &a = s.deformed[t[0]], &b = s.deformed[t[1]], &c = s.deformed[t[2]];
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double nx = e1[1] * e2[2] - e1[2] * e2[1], ny = e1[2] * e2[0] - e1[0] * e2[2],
                 nz = e1[0] * e2[1] - e1[1] * e2[0];
    total += 0.5 * std::sqrt(nx * nx + ny * ny + nz * nz);
    cumulative.push_back(total);
  }
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<calibration::Point> pts;
  for (int i = 0; i < n; ++i)
  {
    const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), U(gen) * total);
    const auto& t = s.triangles[std::min<std::size_t>(it - cumulative.begin(), s.triangles.size() - 1)];
    // Uniform point of a triangle: sqrt trick (Osada et al. 2002).
    const double r1 = std::sqrt(U(gen)), r2 = U(gen);
    const double wa = 1 - r1, wb = r1 * (1 - r2), wc = r1 * r2;
    calibration::Point p;
    for (int k = 0; k < 3; ++k)
      p[k] = wa * s.deformed[t[0]][k] + wb * s.deformed[t[1]][k] + wc * s.deformed[t[2]][k]
             + noise(gen);
    pts.push_back(p);
  }
  return pts;
}
} // namespace

Recording synthetic_recording(const Config& c, const RecordingOptions& o, MPI_Comm comm)
{
  HalfCapSpec::from(c).require_parametric_cap("record (the truth is meshed finer)");
  if (o.points < 10 || o.points > static_cast<int>(calibration::max_recorded_points))
    throw InputError(fmt::format("--points = {} is out of range: allowed [10, 1000000]", o.points));
  if (!(o.noise >= 0) || o.noise > 0.02)
    throw InputError(fmt::format("--noise = {} m is out of range: allowed [0, 0.02] m", o.noise));
  if (!(o.value >= 0))
    throw InputError(fmt::format("--value = {} is out of range: allowed >= 0", o.value));
  Config truth = c;
  const double h = o.mesh_size > 0 ? o.mesh_size : HalfCapSpec::from(c).mesh_size / 1.5;
  truth.set("geometry.mesh_size", h);
  double value = 0;
  if (!o.hidden.empty())
  {
    const Candidate& cand = candidate(o.hidden);
    if (!cand.applicable(c))
      throw InputError(fmt::format("--hidden {}: the case already has this physics on "
                                   "(terms.{} = true): nothing would be hidden",
                                   o.hidden, o.hidden));
    value = o.value > 0 ? o.value : cand.typical;
    truth = cand.with(truth, value);
  }
  truth.validate(); // e.g. mesh_size range

  const CaseOptions truth_case = CaseOptions::from(truth);
  Model model(build_neutral_mesh(truth, comm), Constraints{true, truth_case.fixed_base});
  apply_parameters(truth, model);
  NewtonSolver newton(model, NewtonOptions::from(truth));
  ObservableProbe probe(model, truth_case.geometry.nipple());
  std::mt19937 gen(o.seed); // same sequence on every rank; used on rank 0
  std::normal_distribution<double> noise(0.0, o.noise);
  int rank;
  MPI_Comm_rank(comm, &rank);

  Recording rec;
  rec.noise_sigma = o.noise > 0 ? o.noise : 1e-6;
  for (const char* name : {"R", "H", "rho"}) // a-priori values, named like --fit
    rec.known[name] = truth.number(calibration::fit_alias(name).key);
  for (const auto& p : requested_postures(truth))
  {
    log::info("recording: solving posture '{}' (truth mesh {:.3g} mm)", p.name, 1e3 * h);
    const Observables ob = solve_posture(model, newton, probe, p, truth).observables;
    const SkinSurface s = gather_skin_surface(model); // complete on rank 0
    calibration::RecordedPosture q;
    q.name = p.name;
    q.theta_deg = p.theta_deg;
    if (rank == 0)
      q.points = sample_surface(s, o.points, o.noise, gen);
    q.nipple = calibration::Point{ob.nipple[0] + noise(gen), ob.nipple[1] + noise(gen),
                                  ob.nipple[2] + noise(gen)};
    rec.postures.push_back(std::move(q));
  }
  rec.truth = {{"generator", "breastsim record"},
               {"hidden", o.hidden.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.hidden)},
               {"parameter", o.hidden.empty() ? "" : candidate(o.hidden).parameter},
               {"value", value},
               {"mesh_size", h},
               {"seed", o.seed},
               {"noise", o.noise},
               {"case", truth.to_json()}};
  return rec; // points only on rank 0
}
} // namespace breastsim::diagnosis
