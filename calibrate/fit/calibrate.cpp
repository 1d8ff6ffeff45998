#include "calibrate.hpp"
#include "calibration_plots.hpp"
#include "checkpoint.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "misfit.hpp"
#include "output.hpp"
#include "uncertainty.hpp"
#include <chrono>
#include <cmath>
#include <fmt/format.h>

namespace breastsim::calibration
{
namespace
{
std::string parameter_text(const std::vector<FitParameter>& fit, const std::vector<double>& y)
{
  std::string s;
  for (std::size_t j = 0; j < fit.size(); ++j)
    s += fmt::format("{}{} = {:.5g} {}", j ? ", " : "", fit[j].name, std::exp(y[j]), fit[j].unit);
  return s;
}

/// Per measurement before/after; `d` is the model-error correction (empty:
/// none), included in model_after.
nlohmann::json misfit_json(const Measurements& data, const std::vector<Observables>& before,
                           const std::vector<Observables>& after, const std::vector<double>& d)
{
  auto rows = nlohmann::json::array();
  for (std::size_t i = 0; i < data.items.size(); ++i)
  {
    const auto& m = data.items[i];
    const double di = d.empty() ? 0.0 : d[i];
    const double b = model_value(m, before), a = model_value(m, after) + di;
    rows.push_back({{"measurement", m.label},
                    {"measured", m.value},
                    {"sigma", m.sigma},
                    {"model_before", b},
                    {"model_after", a},
                    {"model_error_correction", di},
                    {"weighted_residual_before", (b - m.value) / m.sigma},
                    {"weighted_residual_after", (a - m.value) / m.sigma}});
  }
  return rows;
}
} // namespace

CalibrationResult calibrate(const Config& start, const Measurements& data,
                            const std::vector<FitParameter>& fit, const CalibrateOptions& o,
                            MPI_Comm comm)
{
  const auto t0 = std::chrono::steady_clock::now();
  check_algorithm(o.optimizer.algorithm);
  check_identifiable(fit);
  Checkpoint cp;
  if (o.resume)
    cp = read_checkpoint(o.checkpoint, fit);
  std::vector<std::string> names;
  for (const auto& p : fit)
    names.push_back(p.name);

  auto warnings = nlohmann::json::array();
  if (!o.morph && changes_geometry(fit))
  {
    const std::string w = "remeshing for R, H (--remesh): the misfit jumps with the mesh topology, "
                          "so finite-difference gradients and the intervals of R and H are "
                          "unreliable (use the default mesh morphing)";
    warnings.push_back(w);
    log::warn("{}", w);
  }
  ForwardModel forward(data.postures, comm, o.morph);
  Objective f(start, data, fit, forward, cp.evaluations);
  // Every evaluation, for the misfit-history plot: stage is "start",
  // "fit", "corrected fit" or "uncertainty" (Jacobian at the optimum).
  auto history = nlohmann::json::array();
  std::string stage = "start";
  f.on_evaluation(
      [&](const Evaluation& e)
      {
        nlohmann::json h = {{"evaluation", e.index}, {"chi2", e.chi2}, {"stage", stage}};
        for (std::size_t j = 0; j < fit.size(); ++j)
          h["parameters"][fit[j].name] = std::exp(e.y[j]);
        history.push_back(h);
        log::info("eval {:>4}  chi2 = {:<12.6g} {}{}", e.index, e.chi2, parameter_text(fit, e.y),
                  e.best ? "  *" : "");
        if (!o.checkpoint.empty())
          write_checkpoint(o.checkpoint, {names, f.best_y(), f.best_chi2(), e.index});
      });

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

  OptimizerOptions oo = o.optimizer;
  OptimizerResult res;
  const int done = f.evaluations();
  oo.max_evals = o.resume ? oo.max_evals - cp.evaluations : oo.max_evals;
  stage = "fit";
  if (oo.max_evals > 0)
    res = minimise(f, y0, oo);
  else
    res = {f.best_y(), f.best_chi2(), "evaluation budget (--max-evals) used up before resuming"};
  log::info("optimiser ({}): {} after {} evaluations", oo.algorithm, res.stop_reason,
            f.evaluations() - done);

  // Model-error correction (approximation-error approach): the
  // discretisation error of the fit mesh at the current parameters,
  // d_i = G_i(fine mesh) - G_i(fit mesh), is added to the model and the fit
  // repeated from its optimum (--max-evals per pass). d depends on the
  // parameters, so this is iterated to a fixed point: until no ln p moves by
  // more than correction_tolerance, at most correction_passes times.
  nlohmann::json correction_json;
  if (o.correction_mesh_size > 0)
  {
    ForwardModel fine_model(data.postures, comm, o.morph);
    auto passes = nlohmann::json::array();
    OptimizerOptions oc = oo;
    // A small first step keeps BOBYQA near the previous optimum (0.2 in ln p
    // wandered over 100+ evaluations).
    oc.initial_step = std::min(oo.initial_step, 0.02);
    for (int pass = 1; pass <= o.correction_passes; ++pass)
    {
      Config fine = with_parameters(start, fit, res.y);
      fine.set("geometry.mesh_size", o.correction_mesh_size);
      fine.validate();
      f.residuals(res.y);
      const std::vector<Observables> coarse = f.observables(); // without the correction
      log::info("model-error correction, pass {}: solving the fitted case on a {:.4g} mm mesh",
                pass, 1e3 * o.correction_mesh_size);
      const std::vector<Observables> fine_obs = fine_model.solve(fine);
      std::vector<double> d;
      for (const auto& item : data.items)
        d.push_back(model_value(item, fine_obs) - model_value(item, coarse));
      f.set_correction(d);
      nlohmann::json at = nlohmann::json::object(); // where d was computed
      for (std::size_t j = 0; j < fit.size(); ++j)
        at[fit[j].name] = std::exp(res.y[j]);
      stage = "corrected fit";
      const int before = f.evaluations();
      const std::vector<double> y_prev = res.y;
      res = minimise(f, res.y, oc);
      // Converged when every parameter moved by less than the tolerance in
      // ln p, or by less than a tenth of its standard error (a parameter the
      // data do not determine drifts along its flat valley from pass to pass).
      const Matrix J = f.jacobian(res.y, oo.fd_step);
      const std::vector<double> se = gauss_newton_uncertainty(J, res.y, names).se_log;
      double moved = 0, moved_se = 0; // largest change of ln p, and in units of SE
      bool converged = true;
      for (std::size_t j = 0; j < fit.size(); ++j)
      {
        const double dy = std::abs(res.y[j] - y_prev[j]);
        moved = std::max(moved, dy);
        moved_se = std::max(moved_se, dy / se[j]);
        converged = converged && (dy < o.correction_tolerance || dy < 0.1 * se[j]);
      }
      log::info("corrected fit, pass {}: {} after {} evaluations; largest change of ln p {:.3g} "
                "({:.2g} SE)",
                pass, res.stop_reason, f.evaluations() - before, moved, moved_se);
      passes.push_back({{"at_parameters", at},
                        {"evaluations", f.evaluations() - before},
                        {"largest_change_ln_p", moved},
                        {"largest_change_in_se", moved_se},
                        {"converged", converged}});
      if (converged)
        break;
    }
    if (!passes.back()["converged"].get<bool>())
    {
      const std::string w = fmt::format(
          "model-error correction: not converged after {} passes (the last moved ln p by {:.3g}); "
          "the remaining bias is not in the intervals",
          passes.size(), passes.back()["largest_change_ln_p"].get<double>());
      warnings.push_back(w);
      log::warn("{}", w);
    }
    correction_json = {{"mesh_size", o.correction_mesh_size},
                       {"fine_posture_solves", fine_model.posture_solves()},
                       {"unknowns_fine", fine_model.dofs()},
                       {"passes", passes}};
  }

  // Observables and uncertainty at the optimum.
  const double chi2_after = f.chi2(res.y);
  const std::vector<Observables> obs_after = f.observables();
  stage = "uncertainty";
  const Matrix J = f.jacobian(res.y, oo.fd_step);
  const std::size_t m = data.items.size(), n = fit.size();
  const double reduced_chi2 = m > n ? chi2_after / double(m - n) : std::nan("");
  const double variance_factor = reduced_chi2 > 1 ? reduced_chi2 : 1.0;
  if (variance_factor > 1)
    log::warn("reduced chi2 = {:.3g} > 1: the model does not fit within the stated sigmas (model "
              "or discretisation error, or optimistic sigmas); intervals widened by {:.3g}",
              reduced_chi2, std::sqrt(variance_factor));
  const Uncertainty u = gauss_newton_uncertainty(J, res.y, names, variance_factor);

  CalibrationResult out;
  out.calibrated = with_parameters(start, fit, res.y);
  nlohmann::json& rep = out.report;
  rep["measurements"] = o.measurements_source;
  rep["algorithm"] = oo.algorithm;
  rep["stop_reason"] = res.stop_reason;
  rep["fit"] = nlohmann::json::array();
  for (std::size_t j = 0; j < fit.size(); ++j)
  {
    const double p = std::exp(res.y[j]);
    rep["fit"].push_back({{"name", fit[j].name},
                          {"key", fit[j].key},
                          {"unit", fit[j].unit},
                          {"initial", std::exp(y_case[j])},
                          {"fitted", p},
                          {"standard_error", p * u.se_log[j]},
                          {"relative_standard_error", u.se_log[j]},
                          {"interval_95", {u.interval[j][0], u.interval[j][1]}},
                          {"bounds", {fit[j].lower, fit[j].upper}},
                          {"at_bound", p <= fit[j].lower * (1 + 1e-6) || p >= fit[j].upper * (1 - 1e-6)},
                          {"flag", u.flags[j]}});
    if (!u.flags[j].empty())
    {
      warnings.push_back(fit[j].name + ": " + u.flags[j]);
      log::warn("{}: {}", fit[j].name, u.flags[j]);
    }
  }
  rep["correlation"] = {{"parameters", names}, {"matrix", u.correlation}};
  rep["misfit"] = {{"chi2_before", chi2_before},
                   {"chi2_after", chi2_after},
                   {"measurements", m},
                   {"reduced_chi2_after", reduced_chi2},
                   {"interval_widening", std::sqrt(variance_factor)},
                   {"per_measurement", misfit_json(data, obs_before, obs_after, f.correction())}};
  if (!correction_json.is_null())
    rep["model_error_correction"] = correction_json;
  rep["history"] = history;
  rep["warnings"] = warnings;
  rep["evaluations"] = f.evaluations();
  rep["posture_solves"] = forward.posture_solves();
  rep["warm_started_solves"] = forward.warm_starts();
  rep["meshes_built"] = forward.meshes_built();
  rep["mesh_morphs"] = forward.morphs();
  rep["unknowns"] = forward.dofs();
  rep["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The calibrated model in each measured posture, for the pictures (not
  // counted above: solved after the report's counts).
  out.surfaces = forward.surfaces(out.calibrated);
  return out;
}

void write_calibration(const CalibrationResult& r, const OutputTarget& out, MPI_Comm comm,
                       const CalibrationOutputOptions& o)
{
  OutputDir dir(out, comm);
  write_text(dir.path() / "calibrated.toml", r.calibrated.to_toml(), comm);
  write_json(dir.path() / "report.json", r.report, comm);
  for (const auto& s : r.surfaces)
    write_json(dir.path() / ("surface_" + s["posture"].get<std::string>() + ".json"), s, comm);
  if (o.pictures)
    render_calibration_pictures(dir.path(), o.picture_size, comm);
  dir.commit();
}

std::string calibration_table(const nlohmann::json& rep)
{
  std::string s = fmt::format("{:<10} {:>12} {:>12} {:>9} {:>27}  {}\n", "parameter", "initial",
                              "fitted", "rel. SE", "95 % interval", "unit");
  for (const auto& p : rep["fit"])
  {
    const double se = p["relative_standard_error"].is_number()
                          ? p["relative_standard_error"].get<double>()
                          : std::nan("");
    s += fmt::format("{:<10} {:>12.5g} {:>12.5g} {:>8.2f}% [{:>12.5g}, {:>12.5g}]  {}{}\n",
                     p["name"].get<std::string>(), p["initial"].get<double>(),
                     p["fitted"].get<double>(), 100 * se,
                     p["interval_95"][0].is_number() ? p["interval_95"][0].get<double>() : 0.0,
                     p["interval_95"][1].is_number() ? p["interval_95"][1].get<double>()
                                                     : std::numeric_limits<double>::infinity(),
                     p["unit"].get<std::string>(),
                     p["flag"].get<std::string>().empty() ? "" : "  ! " + p["flag"].get<std::string>());
  }
  s += fmt::format("chi2 {:.4g} -> {:.4g} ({} measurements); {} evaluations, {} posture solves "
                   "({} warm-started), {:.1f} s\n",
                   rep["misfit"]["chi2_before"].get<double>(), rep["misfit"]["chi2_after"].get<double>(),
                   rep["misfit"]["measurements"].get<int>(), rep["evaluations"].get<int>(),
                   rep["posture_solves"].get<int>(), rep["warm_started_solves"].get<int>(),
                   rep["wall_time_s"].get<double>());
  return s;
}
} // namespace breastsim::calibration
