// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_calibration.hpp"
#include "breastsim_registry.hpp"
#include "case_options.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "mesh_from_gmsh.hpp"
#include "msh_writer.hpp"
#include "output.hpp"
#include "model_setup.hpp"
#include "newton.hpp"
#include "on_root.hpp"
#include "solver_options.hpp"
#include "surface_distance.hpp"
#include "surface_export.hpp"
#include "timer.hpp"
#include "warm_start.hpp"
#include <algorithm>
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <fmt/format.h>
#include <functional>
#include <utility>

namespace breastsim::calibration
{
namespace
{
/// One evaluation: the neutral state of the meshed scan for case `c` and the
/// signed normal distances of each target scan's points to its posture's
/// simulated skin (every rank gets them).
struct ScanEvaluation
{
  std::vector<std::vector<double>> distances; ///< per target, per point [m]
  std::vector<double> reference;              ///< rank 0, with keep_reference
  InverseReport inverse;
};

ScanEvaluation evaluate(const ScanCalibrationRequest& r, const meshes::TaggedMesh& mesh, const Config& c,
                        const std::vector<const ScanPoints*>& targets, bool keep_reference, MPI_Comm comm)
{
  const CaseOptions co = CaseOptions::from(c);
  Model model(to_dolfinx(comm, mesh, mesh.order), Constraints{true, co.fixed_base});
  apply_parameters(c, model);
  const SolverOptions so = SolverOptions::from(c);
  NewtonSolver newton(model, so.newton);
  double f = set_gravity(model, gravity_vector(r.source.posture.theta_deg, co.gravity));
  ScanEvaluation e;
  e.inverse = inverse_neutral_state(model, newton, r.inverse, f);
  if (keep_reference)
    e.reference = gather_geometry_nodes(*model.mesh().mesh, mesh.num_nodes());
  const Guess last{[](Model&, std::string&) { return true; }, "the neutral state's u", true};
  double theta = r.source.posture.theta_deg; // u is the inverse's forward solve in the source posture
  for (const ScanPoints* t : targets)
  {
    std::vector<double> d(t->points.size());
    if (t->posture.theta_deg != theta)
    {
      theta = t->posture.theta_deg;
      f = set_gravity(model, gravity_vector(t->posture.theta_deg, co.gravity));
      solve_at_full_load(model, newton, last, r.inverse.ramp,
                         fmt::format("scan calibration, posture {}", t->posture.name), f);
    }
    const SkinSurface s = gather_skin_surface(model);
    if (rank_of(comm) == 0)
    {
      const std::vector<SurfaceMatch> m = match_points(s, t->points);
      for (std::size_t i = 0; i < m.size(); ++i)
        d[i] = m[i].distance;
    }
    MPI_Bcast(d.data(), static_cast<int>(d.size()), MPI_DOUBLE, 0, comm);
    e.distances.push_back(std::move(d));
  }
  return e;
}

ScanDistance distance_summary(const ScanPoints& s, const std::vector<double>& d, double margin)
{
  ScanDistance out{s.file, s.posture.name, s.points.size(), 0, 0, 0, 0, s.sigma};
  double sum = 0, sum_all = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
  {
    sum_all += d[i] * d[i];
    if (s.points[i][1] < margin)
      continue;
    ++out.used;
    sum += d[i] * d[i];
    out.max = std::max(out.max, std::abs(d[i]));
  }
  out.rms = std::sqrt(sum / std::max<std::size_t>(out.used, 1));
  out.rms_all = std::sqrt(sum_all / std::max<std::size_t>(d.size(), 1));
  return out;
}

nlohmann::json distance_json(const ScanDistance& d)
{
  return {{"file", d.file},       {"posture", d.posture}, {"points", d.points},
          {"points_used", d.used}, {"rms_mm", 1e3 * d.rms}, {"max_mm", 1e3 * d.max},
          {"rms_all_points_mm", 1e3 * d.rms_all}, {"sigma_mm", 1e3 * d.sigma}};
}
} // namespace

namespace
{
/// The misfit of a scan calibration: each fitted scan point's normal
/// distance to the simulated skin over its scan's sigma, r_k = d_k / sigma
/// (points within the chest margin left out), for the parameters y = ln p.
class ScanMisfit
{
public:
  ScanMisfit(const ScanCalibrationRequest& r, MPI_Comm comm) : mesh(&r.mesh), _r(r), _comm(comm)
  {
    for (const auto& p : r.parameters)
      names.push_back(p.name);
    for (const auto& s : r.fit)
      _targets.push_back(&s);
    for (std::size_t t = 0; t < r.fit.size(); ++t)
      for (std::size_t i = 0; i < r.fit[t].points.size(); ++i)
        if (r.fit[t].points[i][1] >= r.chest_margin)
          _index.emplace_back(t, i);
    if (_index.size() < 10 * r.parameters.size())
      throw InputError(fmt::format("scan calibration: only {} scan points lie {:.1f} mm or more off the chest "
                                   "(--chest-margin): too few for {} parameters",
                                   _index.size(), 1e3 * r.chest_margin, r.parameters.size()));
  }

  /// The start's evaluation (its distance summaries into `at_start`); its
  /// residuals are kept for the fit's first call.
  void evaluate_start(std::vector<double> y0, std::vector<ScanDistance>& at_start)
  {
    const ScanEvaluation e0 = evaluate(_r, _r.mesh, _r.start, _targets, false, _comm);
    for (std::size_t t = 0; t < _r.fit.size(); ++t)
      at_start.push_back(distance_summary(_r.fit[t], e0.distances[t], _r.chest_margin));
    _y_start = std::move(y0);
    _r_start = residuals(e0.distances);
    ++_evaluation;
  }

  /// Where the next fit starts: a failed solve there is an error.
  void start_at(std::vector<double> y) { _y_start = std::move(y); }

  std::vector<double> operator()(const std::vector<double>& y)
  {
    if (y == _y_start && !_r_start.empty())
      return std::exchange(_r_start, {});
    const Config c = with_parameters(_r.start, _r.parameters, y);
    std::string ps;
    for (std::size_t j = 0; j < y.size(); ++j)
      ps += fmt::format("{}{} = {:.6g} {}", j ? ", " : "", names[j], std::exp(y[j]), _r.parameters[j].unit);
    try
    {
      const ScanEvaluation e = evaluate(_r, *mesh, c, _targets, false, _comm);
      const std::vector<double> v = residuals(e.distances);
      double chi2 = 0;
      for (double x : v)
        chi2 += x * x;
      log::info("scan calibration, evaluation {}: {}: chi2 {:.6g} ({} inverse iterations)", ++_evaluation, ps,
                chi2, e.inverse.iterations.size());
      return v;
    }
    catch (const SolveError& err)
    {
      if (y == _y_start)
        throw;
      // A trial step the material cannot hold: a large misfit rejects the step.
      log::warn("scan calibration, evaluation {}: {}: {} (step rejected)", ++_evaluation, ps, err.what());
      return std::vector<double>(_index.size(), 1e3);
    }
  }

  std::vector<std::string> names;
  const meshes::TaggedMesh* mesh; ///< the mesh the evaluations use

private:
  std::vector<double> residuals(const std::vector<std::vector<double>>& d) const
  {
    std::vector<double> v(_index.size());
    for (std::size_t k = 0; k < _index.size(); ++k)
      v[k] = d[_index[k].first][_index[k].second] / _r.fit[_index[k].first].sigma;
    return v;
  }

  const ScanCalibrationRequest& _r;
  MPI_Comm _comm;
  std::vector<const ScanPoints*> _targets;
  std::vector<std::pair<std::size_t, std::size_t>> _index; ///< (target, point) of each residual
  int _evaluation = 0;
  std::vector<double> _y_start, _r_start;
};

std::size_t cells_on_root(const meshes::TaggedMesh& m, MPI_Comm comm)
{
  std::size_t n = m.num_cells();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, 0, comm);
  return n;
}

/// The fit's values, misfit and Gauss-Newton uncertainty into `res`.
void record_fit(const LsqResult& lsq, const std::vector<double>& y0, const std::vector<std::string>& names,
                ScanCalibrationResult& res)
{
  res.residuals = lsq.r.size();
  res.chi2 = lsq.chi2;
  const double dof = std::max<double>(1, double(lsq.r.size()) - double(y0.size()));
  res.reduced_chi2 = lsq.chi2 / dof;
  res.evaluations = lsq.evaluations;
  res.iterations = lsq.iterations;
  res.stop_reason = lsq.stop_reason;
  res.uncertainty = gauss_newton_uncertainty(lsq.J, lsq.y, names, std::max(1.0, res.reduced_chi2));
  for (std::size_t j = 0; j < y0.size(); ++j)
  {
    res.start.push_back(std::exp(y0[j]));
    res.value.push_back(std::exp(lsq.y[j]));
  }
  res.se_log_noise = res.uncertainty.se_log;
}

/// The fit again on the coarser mesh: SE_mesh = |ln p_h - ln p_coarse| /
/// (ratio - 1) added to each parameter's SE, the intervals widened.
void widen_by_coarse_fit(const ScanCalibrationRequest& r, ScanMisfit& f, const LsqResult& lsq,
                         const std::vector<double>& lo, const std::vector<double>& hi,
                         ScanCalibrationResult& res, MPI_Comm comm)
{
  res.coarse_tetrahedra = cells_on_root(r.coarse_mesh, comm);
  log::info("scan calibration: the fit again on a mesh {:g} times coarser ({} tetrahedra), for its "
            "discretisation error", r.mesh_ratio, res.coarse_tetrahedra);
  f.mesh = &r.coarse_mesh;
  f.start_at(lsq.y);
  const LsqResult coarse = levenberg_marquardt(std::ref(f), lsq.y, lo, hi, r.lsq);
  f.mesh = &r.mesh;
  res.evaluations += coarse.evaluations;
  auto& u = res.uncertainty;
  for (std::size_t j = 0; j < lsq.y.size(); ++j)
  {
    res.coarse_value.push_back(std::exp(coarse.y[j]));
    res.se_log_mesh.push_back(std::abs(lsq.y[j] - coarse.y[j]) / (r.mesh_ratio - 1));
    widen_interval(u, j, std::exp(lsq.y[j]), res.se_log_mesh[j]);
    if (u.flags[j].empty() && u.se_log[j] > max_se_log)
      u.flags[j] = fmt::format("poorly determined: relative standard error {:.0f} %", 100 * u.se_log[j]);
  }
}

/// The fitted neutral state and every scan against it (the source scan, the
/// fitted ones, the held-out ones); the reference mesh and nipple into the
/// calibrated case.
void evaluate_fitted(const ScanCalibrationRequest& r, ScanCalibrationResult& res, MPI_Comm comm)
{
  std::vector<const ScanPoints*> all = {&r.source};
  for (const auto& s : r.fit)
    all.push_back(&s);
  for (const auto& s : r.predict)
    all.push_back(&s);
  const ScanEvaluation e = evaluate(r, r.mesh, res.calibrated, all, true, comm);
  res.inverse = e.inverse;
  for (std::size_t t = 0; t < all.size(); ++t)
    (t <= r.fit.size() ? res.fitted : res.predicted)
        .push_back(distance_summary(*all[t], e.distances[t], r.chest_margin));
  if (rank_of(comm) == 0)
  {
    res.reference = r.mesh;
    res.reference.x = e.reference;
    // A full breast's nipple may leave x = 0: the reference is shifted
    // rigidly along x to keep it there (as neutral-state does).
    const bool half = std::count(r.mesh.facet_tags.begin(), r.mesh.facet_tags.end(), generated::tag("symmetry")) > 0;
    if (!half)
    {
      res.shift_x = -res.reference.x[3 * r.nipple_node];
      for (std::size_t n = 0; n < res.reference.num_nodes(); ++n)
        res.reference.x[3 * n] += res.shift_x;
    }
    for (int k = 0; k < 3; ++k)
      res.nipple[k] = res.reference.x[3 * r.nipple_node + k];
  }
  MPI_Bcast(res.nipple.data(), 3, MPI_DOUBLE, 0, comm);
  MPI_Bcast(&res.shift_x, 1, MPI_DOUBLE, 0, comm);
  res.calibrated.set("geometry.mesh_file", std::string("reference.msh"));
  res.calibrated.set("geometry.H", res.nipple[1]);
  res.calibrated.set("geometry.nipple_z", res.nipple[2]);
  res.calibrated.set("geometry.refinements", std::int64_t(0));
}
} // namespace

ScanCalibrationResult scan_calibrate(const ScanCalibrationRequest& r, MPI_Comm comm)
{
  const Stopwatch watch("scan calibration");
  ScanCalibrationResult res;
  res.parameters = r.parameters;
  std::vector<double> lo, hi;
  for (const auto& p : r.parameters)
  {
    lo.push_back(std::log(p.lower));
    hi.push_back(std::log(p.upper));
  }
  const std::vector<double> y0 = to_log(r.parameters, r.start);
  ScanMisfit f(r, comm);
  f.evaluate_start(y0, res.at_start);
  const LsqResult lsq = levenberg_marquardt(std::ref(f), y0, lo, hi, r.lsq);
  record_fit(lsq, y0, f.names, res);
  res.mesh_ratio = r.mesh_ratio;
  res.tetrahedra = cells_on_root(r.mesh, comm);
  if (r.mesh_ratio > 0)
    widen_by_coarse_fit(r, f, lsq, lo, hi, res, comm);
  res.calibrated = with_parameters(r.start, r.parameters, lsq.y);
  evaluate_fitted(r, res, comm);
  res.seconds = watch.seconds();
  return res;
}

nlohmann::json scan_calibration_json(const ScanCalibrationResult& r)
{
  auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  nlohmann::json params = nlohmann::json::array();
  for (std::size_t j = 0; j < r.parameters.size(); ++j)
  {
    const auto& u = r.uncertainty;
    params.push_back({{"name", r.parameters[j].name},
                      {"key", r.parameters[j].key},
                      {"unit", r.parameters[j].unit},
                      {"start", r.start[j]},
                      {"value", r.value[j]},
                      {"bounds", {r.parameters[j].lower, r.parameters[j].upper}},
                      {"se_log", std::isfinite(u.se_log[j]) ? nlohmann::json(u.se_log[j]) : nlohmann::json()},
                      {"relative_se_percent", std::isfinite(u.se_log[j]) ? nlohmann::json(100 * u.se_log[j])
                                                                         : nlohmann::json()},
                      {"interval95", {u.interval[j][0], u.interval[j][1]}},
                      {"se_log_noise", finite(r.se_log_noise[j])},
                      {"se_log_mesh", j < r.se_log_mesh.size() ? finite(r.se_log_mesh[j]) : nlohmann::json()},
                      {"value_coarse_mesh", j < r.coarse_value.size() ? nlohmann::json(r.coarse_value[j])
                                                                       : nlohmann::json()},
                      {"flag", u.flags[j]}});
  }
  nlohmann::json corr = r.uncertainty.singular ? nlohmann::json() : nlohmann::json(r.uncertainty.correlation);
  auto list = [](const std::vector<ScanDistance>& v)
  {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& d : v)
      a.push_back(distance_json(d));
    return a;
  };
  nlohmann::json it = nlohmann::json::array();
  for (const auto& i : r.inverse.iterations)
    it.push_back({{"mismatch_rms_m", i.rms_mismatch}, {"mismatch_max_m", i.max_mismatch}});
  return {{"method", "neutral state by the inverse solve from the first scan; forward solves to the other scans' "
                     "postures; Levenberg-Marquardt on their points' normal distances / sigma in y = ln p; "
                     "Gauss-Newton covariance (scaled by the reduced chi2 when above 1); se_log = hypot(se_log_noise, "
                     "se_log_mesh), se_log_mesh = |ln p - ln p_coarse| / (mesh_ratio - 1) from the fit on a mesh "
                     "mesh_ratio times coarser"},
          {"mesh_ratio", r.mesh_ratio},
          {"tetrahedra", r.tetrahedra},
          {"coarse_tetrahedra", r.coarse_tetrahedra},
          {"parameters", params},
          {"correlation", corr},
          {"singular", r.uncertainty.singular},
          {"chi2", r.chi2},
          {"reduced_chi2", r.reduced_chi2},
          {"residuals", r.residuals},
          {"evaluations", r.evaluations},
          {"iterations", r.iterations},
          {"stop_reason", r.stop_reason},
          {"scans_at_start", list(r.at_start)},
          {"scans_fitted", list(r.fitted)},
          {"scans_predicted", list(r.predicted)},
          {"neutral_state", {{"inverse_iterations", it}, {"converged", r.inverse.converged},
                             {"nipple_m", r.nipple}, {"reference_shift_x_m", r.shift_x}}},
          {"wall_time_s", r.seconds}};
}

void write_scan_calibration(const ScanCalibrationRequest& r, const ScanCalibrationResult& res,
                            const nlohmann::json& inputs, const OutputTarget& out, MPI_Comm comm)
{
  OutputDir dir(out, comm);
  if (rank_of(comm) == 0)
  {
    std::map<int, std::string> names;
    for (const char* n : {"base", "skin", "symmetry"})
      if (std::count(r.mesh.facet_tags.begin(), r.mesh.facet_tags.end(), generated::tag(n)) > 0)
        names[generated::tag(n)] = n;
    meshes::write_msh22(r.mesh, names, dir.path() / "scan.msh");
    meshes::write_msh22(res.reference, names, dir.path() / "reference.msh");
  }
  std::string head = "# breastsim scan-calibrate: the neutral state (reference.msh) and the material fitted to the scans\n";
  for (std::size_t j = 0; j < res.parameters.size(); ++j)
    head += fmt::format("#   {} = {:.6g} {} (95 % interval [{:.6g}, {:.6g}])\n", res.parameters[j].key, res.value[j],
                        res.parameters[j].unit, res.uncertainty.interval[j][0], res.uncertainty.interval[j][1]);
  write_text(dir.path() / "case.toml", head + res.calibrated.to_toml(), comm);
  nlohmann::json j = scan_calibration_json(res);
  j["inputs"] = inputs;
  write_json(dir.path() / "report.json", j, comm);
  dir.commit();
}

std::string scan_calibration_table(const ScanCalibrationResult& r)
{
  std::string s = fmt::format("scan calibration: {} evaluations, {} iterations ({}); chi2 {:.4g}, reduced {:.3f}, "
                              "{:.1f} s\n",
                              r.evaluations, r.iterations, r.stop_reason, r.chi2, r.reduced_chi2, r.seconds);
  for (std::size_t j = 0; j < r.parameters.size(); ++j)
  {
    s += fmt::format("  {:<6} {:12.6g} {}  (start {:.6g}; SE {:.2f} %, 95 % interval [{:.6g}, {:.6g}]) {}\n",
                     r.parameters[j].name, r.value[j], r.parameters[j].unit, r.start[j],
                     100 * r.uncertainty.se_log[j], r.uncertainty.interval[j][0], r.uncertainty.interval[j][1],
                     r.uncertainty.flags[j]);
    if (j < r.se_log_mesh.size())
      s += fmt::format("         SE from the noise {:.2f} %, from the mesh {:.2f} % (coarser mesh: {:.6g} {})\n",
                       100 * r.se_log_noise[j], 100 * r.se_log_mesh[j], r.coarse_value[j], r.parameters[j].unit);
  }
  auto rows = [&](const char* what, const std::vector<ScanDistance>& v)
  {
    for (const auto& d : v)
      s += fmt::format("  {:<9} {:<10} RMS {:.3f} mm, max {:.3f} mm ({} of {} points off the chest; all points "
                       "{:.3f} mm)\n",
                       what, d.posture, 1e3 * d.rms, 1e3 * d.max, d.used, d.points, 1e3 * d.rms_all);
  };
  rows("start", r.at_start);
  rows("fitted", r.fitted);
  rows("predicted", r.predicted);
  return s;
}
} // namespace breastsim::calibration
