// SPDX-License-Identifier: LGPL-3.0-or-later
#include "calibrate.hpp"
#include "geometry_options.hpp"
#include "calibration_report.hpp"
#include "checkpoint.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "misfit.hpp"
#include "timer.hpp"
#include "uncertainty.hpp"
#include <cmath>
#include <fmt/format.h>

namespace breastsim::calibration
{
namespace
{
std::vector<std::string> names_of(const std::vector<FitParameter>& fit)
{
  std::vector<std::string> names;
  for (const auto& p : fit)
    names.push_back(p.name);
  return names;
}

/// One calibration in progress.
struct Run
{
  Run(const Config& s, const Measurements& d, const std::vector<FitParameter>& p,
      const CalibrateOptions& opt, Objective& objective)
      : start(s), data(d), fit(p), o(opt), names(names_of(p)), f(objective)
  {
  }

  const Config& start;
  const Measurements& data;
  const std::vector<FitParameter>& fit;
  const CalibrateOptions& o;
  std::vector<std::string> names;
  Objective& f;
  Warnings warnings;
  /// Every evaluation, for the misfit-history plot: stage is "start",
  /// "fit", "corrected fit" or "uncertainty" (Jacobian at the optimum).
  nlohmann::json history = nlohmann::json::array();
  std::string stage = "start";
};

/// After every evaluation: the history, a progress line, the checkpoint.
void record_evaluations(Run& run)
{
  run.f.on_evaluation(
      [&run](const Evaluation& e)
      {
        nlohmann::json h = {{"evaluation", e.index}, {"chi2", e.chi2}, {"stage", run.stage}, {"best", e.best}};
        for (std::size_t j = 0; j < run.fit.size(); ++j)
          h["parameters"][run.fit[j].name] = std::exp(e.y[j]);
        run.history.push_back(h);
        if (run.o.on_evaluation)
          run.o.on_evaluation(h);
        log::info("eval {:>4}  chi2 = {:<12.6g} {}{}", e.index, e.chi2, parameter_text(run.fit, e.y),
                  e.best ? "  *" : "");
        if (!run.o.checkpoint.empty())
          write_checkpoint(run.o.checkpoint, {run.names, run.f.best_y(), run.f.best_chi2(), e.index});
      });
}

/// The optimiser from y0 within what is left of --max-evals (oo.max_evals).
OptimizerResult first_fit(Run& run, const OptimizerOptions& oo, const std::vector<double>& y0)
{
  const int done = run.f.evaluations();
  run.stage = "fit";
  OptimizerResult res;
  if (oo.max_evals > 0)
    res = minimise(run.f, y0, oo);
  else
    res = {run.f.best_y(), run.f.best_chi2(), "evaluation budget (--max-evals) used up before resuming"};
  log::info("optimiser ({}): {} after {} evaluations", oo.algorithm, res.stop_reason,
            run.f.evaluations() - done);
  return res;
}

/// One pass of the model-error correction: d at res.y, then the corrected fit
/// from there (res updated). Converged when every parameter moved by less
/// than the tolerance in ln p, or by less than a tenth of its standard error
/// (a parameter the data do not determine drifts along its flat valley from
/// pass to pass).
nlohmann::json correction_pass(Run& run, ForwardModel& fine_model, int pass, const OptimizerOptions& oo,
                               const OptimizerOptions& oc, OptimizerResult& res)
{
  Objective& f = run.f;
  Config fine = with_parameters(run.start, run.fit, res.y);
  fine.set("geometry.mesh_size", run.o.correction_mesh_size);
  fine.validate();
  f.residuals(res.y);
  const std::vector<Observables> coarse = f.observables(); // without the correction
  log::info("model-error correction, pass {}: solving the fitted case on a {:.4g} mm mesh", pass,
            1e3 * run.o.correction_mesh_size);
  const std::vector<Observables> fine_obs = fine_model.solve(fine);
  std::vector<double> d;
  for (const auto& item : run.data.items)
    d.push_back(model_value(item, fine_obs) - model_value(item, coarse));
  f.set_correction(d);
  nlohmann::json at = nlohmann::json::object(); // where d was computed
  for (std::size_t j = 0; j < run.fit.size(); ++j)
    at[run.fit[j].name] = std::exp(res.y[j]);
  run.stage = "corrected fit";
  const int before = f.evaluations();
  const std::vector<double> y_prev = res.y;
  res = minimise(f, res.y, oc);
  const Matrix J = f.jacobian(res.y, oo.fd_step);
  const std::vector<double> se = gauss_newton_uncertainty(J, res.y, run.names).se_log;
  double moved = 0, moved_se = 0; // largest change of ln p, and in units of SE
  bool converged = true;
  for (std::size_t j = 0; j < run.fit.size(); ++j)
  {
    const double dy = std::abs(res.y[j] - y_prev[j]);
    moved = std::max(moved, dy);
    moved_se = std::max(moved_se, dy / se[j]);
    converged = converged && (dy < run.o.correction_tolerance || dy < 0.1 * se[j]);
  }
  log::info("corrected fit, pass {}: {} after {} evaluations; largest change of ln p {:.3g} "
            "({:.2g} SE)",
            pass, res.stop_reason, f.evaluations() - before, moved, moved_se);
  return {{"at_parameters", at},
          {"evaluations", f.evaluations() - before},
          {"largest_change_ln_p", moved},
          {"largest_change_in_se", moved_se},
          {"converged", converged}};
}

/// Model-error correction (approximation-error approach): the
/// discretisation error of the fit mesh at the current parameters,
/// d_i = G_i(fine mesh) - G_i(fit mesh), is added to the model and the fit
/// repeated from its optimum (--max-evals per pass). d depends on the
/// parameters, so this is iterated to a fixed point: until no ln p moves by
/// more than correction_tolerance, at most correction_passes times.
nlohmann::json correct_model_error(Run& run, const OptimizerOptions& oo, OptimizerResult& res,
                                   MPI_Comm comm)
{
  ForwardModel fine_model(run.data.postures, comm, run.o.morph);
  auto passes = nlohmann::json::array();
  OptimizerOptions oc = oo;
  // A small first step keeps BOBYQA near the previous optimum (docs/CALIBRATION.md).
  oc.initial_step = std::min(oo.initial_step, 0.02);
  for (int pass = 1; pass <= run.o.correction_passes; ++pass)
  {
    passes.push_back(correction_pass(run, fine_model, pass, oo, oc, res));
    if (passes.back()["converged"].get<bool>())
      break;
  }
  if (!passes.back()["converged"].get<bool>())
    run.warnings.add(fmt::format(
        "model-error correction: not converged after {} passes (the last moved ln p by {:.3g}); "
        "the remaining bias is not in the intervals",
        passes.size(), passes.back()["largest_change_ln_p"].get<double>()));
  return {{"mesh_size", run.o.correction_mesh_size},
          {"fine_posture_solves", fine_model.posture_solves()},
          {"unknowns_fine", fine_model.dofs()},
          {"passes", passes}};
}

/// Gauss-Newton uncertainty at the optimum y, widened when the misfit
/// exceeds the stated sigmas; the reduced chi2 (NaN without spare measurements).
Uncertainty uncertainty_at(Run& run, const OptimizerOptions& oo, const std::vector<double>& y,
                           double chi2, double& reduced_chi2, double& variance_factor)
{
  run.stage = "uncertainty";
  const Matrix J = run.f.jacobian(y, oo.fd_step);
  const std::size_t m = run.data.items.size(), n = run.fit.size();
  reduced_chi2 = m > n ? chi2 / double(m - n) : std::nan("");
  variance_factor = reduced_chi2 > 1 ? reduced_chi2 : 1.0;
  if (variance_factor > 1)
    log::warn("reduced chi2 = {:.3g} > 1: the model does not fit within the stated sigmas (model "
              "or discretisation error, or optimistic sigmas); intervals widened by {:.3g}",
              reduced_chi2, std::sqrt(variance_factor));
  return gauss_newton_uncertainty(J, y, run.names, variance_factor);
}

/// A case on a mesh file (a scan's, a neutral state's: full or half) is
/// calibrated on that mesh as it is: its shape is not the cap's R, H, and it
/// has no finer mesh for the model-error correction.
void check_mesh_file_case(const Config& start, const std::vector<FitParameter>& fit,
                          const CalibrateOptions& o)
{
  const std::string mesh_file = HalfCapSpec::from(start).mesh_file;
  if (mesh_file.empty())
    return;
  for (const auto& p : fit)
    if (p.role == generated::FitRole::shape)
      throw InputError(fmt::format(
          "--fit: '{}' ({}) morphs the parametric cap, but the case's mesh is key "
          "'geometry.mesh_file' = \"{}\", whose shape is fixed: fit material parameters only",
          p.name, p.key, mesh_file));
  if (o.correction_mesh_size > 0)
    throw InputError(fmt::format("--correction-mesh-size = {}: the case's mesh is key "
                                 "'geometry.mesh_file' = \"{}\", which is not remeshed finer; "
                                 "leave it at 0",
                                 o.correction_mesh_size, mesh_file));
}
} // namespace

CalibrationResult calibrate(const Config& start, const Measurements& data,
                            const std::vector<FitParameter>& fit, const CalibrateOptions& o,
                            MPI_Comm comm)
{
  const Stopwatch stopwatch("calibrate");
  check_mesh_file_case(start, fit, o);
  check_algorithm(o.optimizer.algorithm);
  check_identifiable(fit);
  Checkpoint cp;
  if (o.resume)
    cp = read_checkpoint(o.checkpoint, fit);
  const CaseGroups groups(comm, o.ranks_per_case, "--ranks-per-case");
  ForwardModel forward(data.postures, groups.comm(), o.morph);
  Objective f(start, data, fit, forward, cp.evaluations);
  if (groups.groups() > 1)
    f.spread_columns(groups);
  Run run(start, data, fit, o, f);
  if (!o.morph && changes_geometry(fit))
    run.warnings.add("remeshing for R, H (--remesh): the misfit jumps with the mesh topology, "
                     "so finite-difference gradients and the intervals of R and H are "
                     "unreliable (use the default mesh morphing)");
  record_evaluations(run);
  if (o.resume)
    f.set_best(cp.best_y, cp.best_chi2); // the checkpoint keeps the best point
  // Misfit of the starting case (the "before" column of the report).
  const std::vector<double> y_case = to_log(fit, start);
  const double chi2_before = f.chi2(y_case);
  const std::vector<Observables> obs_before = f.observables();
  const std::vector<double> y0 = o.resume ? cp.best_y : y_case;
  if (o.resume)
    log::info("resuming after {} evaluations from {} (chi2 = {:.6g})", cp.evaluations,
              parameter_text(fit, y0), cp.best_chi2);
  OptimizerOptions oo = o.optimizer; // --max-evals counts the resumed run's evaluations too
  oo.max_evals = o.resume ? oo.max_evals - cp.evaluations : oo.max_evals;
  OptimizerResult res = first_fit(run, oo, y0);
  nlohmann::json correction_json;
  if (o.correction_mesh_size > 0)
    correction_json = correct_model_error(run, oo, res, groups.comm());

  const double chi2_after = f.chi2(res.y);
  const std::vector<Observables> obs_after = f.observables();
  double reduced_chi2 = 0, variance_factor = 1;
  const Uncertainty u = uncertainty_at(run, oo, res.y, chi2_after, reduced_chi2, variance_factor);

  CalibrationResult out;
  out.calibrated = with_parameters(start, fit, res.y);
  nlohmann::json& rep = out.report;
  rep["measurements"] = o.measurements_source;
  rep["algorithm"] = oo.algorithm;
  rep["stop_reason"] = res.stop_reason;
  rep["fit"] = fit_json(fit, y_case, res.y, u, run.warnings);
  rep["correlation"] = {{"parameters", run.names}, {"matrix", u.correlation}};
  rep["misfit"] = {{"chi2_before", chi2_before},
                   {"chi2_after", chi2_after},
                   {"measurements", data.items.size()},
                   {"reduced_chi2_after", reduced_chi2},
                   {"interval_widening", std::sqrt(variance_factor)},
                   {"per_measurement", misfit_json(data, obs_before, obs_after, f.correction())}};
  if (!correction_json.is_null())
    rep["model_error_correction"] = correction_json;
  rep["history"] = run.history;
  rep["warnings"] = run.warnings.list;
  rep["evaluations"] = f.evaluations();
  rep["posture_solves"] = forward.posture_solves();
  rep["warm_started_solves"] = forward.warm_starts();
  rep["meshes_built"] = forward.meshes_built();
  rep["mesh_morphs"] = forward.morphs();
  rep["unknowns"] = forward.dofs();
  rep["rank_groups"] = groups.groups();
  rep["wall_time_s"] = stopwatch.seconds();
  // The calibrated model in each measured posture, for the pictures (not
  // counted above: solved after the report's counts).
  out.surfaces = forward.surfaces(out.calibrated);
  return out;
}
} // namespace breastsim::calibration
