// `breastsim calibrate MEASUREMENTS.json`: fit case parameters to measurements.
// `breastsim measure CASE.toml`: synthetic measurements from the forward model.
#include "config.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "output.hpp"
#include "calibrate.hpp"
#include "diagnose.hpp"
#include "diagnosis_output.hpp"
#include "json_file.hpp"
#include "measurements.hpp"
#include "recording.hpp"
#include "command.hpp"
#include "overrides.hpp"
#include "synthetic.hpp"
#include "viewer.hpp"
#include <fmt/format.h>
#include <cstdio>
#include <iostream>
#include <memory>

namespace breastsim::cli
{
namespace
{
/// The built-in defaults with "key=value" overrides (load_case needs a file).
Config with_overrides(Config c, const std::vector<std::string>& sets)
{
  for (const auto& s : sets)
  {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--set expects key=value, got '" + s + "'");
    c.set_text(s.substr(0, eq), s.substr(eq + 1));
  }
  return c;
}
} // namespace

Command add_calibrate_command(CLI::App& root)
{
  struct Options
  {
    std::string measurements, case_file, fit = "mu,c", algorithm = "bobyqa", checkpoint,
                                          petsc_options, size = "800x600";
    OutputOption out;
    std::vector<std::string> sets;
    bool resume = false, remesh = false;
    int max_evals = 200;
    double correction_mesh_size = 0;
  };
  auto o = std::make_shared<Options>();
  auto* app = root.add_subcommand(
      "calibrate", "fit tissue/skin/spring parameters and the neutral shape to measurements in "
                   "several postures (docs/CALIBRATION.md)");
  app->add_option("measurements", o->measurements, "measurement file (JSON, SI units), or a 3D "
                                                   "surface recording (breastsim-recording/1)")->required();
  app->add_option("--case", o->case_file,
                  "starting case (TOML); its values are the initial guess (default: built-in "
                  "defaults)");
  app->add_option("--set", o->sets, "override a case key, e.g. --set geometry.mesh_size=0.012");
  app->add_option("--fit", o->fit, "parameters to fit, comma separated: mu, lambda, mu_s, "
                                   "lambda_s, c, R, H, rho")
      ->capture_default_str();
  app->add_option("--algorithm", o->algorithm,
                  "bobyqa, sbplx, neldermead (derivative-free); lbfgs, slsqp, mma (finite-"
                  "difference gradients)")
      ->capture_default_str();
  app->add_option("--max-evals", o->max_evals, "objective evaluations allowed (in total with "
                                               "--resume)")
      ->capture_default_str();
  add_output_option(app, o->out, "output folder (default results/<case.name>_calibrated); "
                                 "replaced on success");
  app->add_option("--checkpoint", o->checkpoint, "checkpoint file (default <out>.checkpoint.json)");
  app->add_flag("--resume", o->resume, "continue from the checkpoint's best point");
  app->add_option("--petsc-options", o->petsc_options, "PETSc options passed through");
  app->add_flag("--remesh", o->remesh, "remesh for every change of R, H instead of morphing the "
                                       "mesh (the misfit is then rough in R, H)");
  app->add_option("--correction-mesh-size", o->correction_mesh_size,
                  "after the fit, correct the model by its discretisation error measured on a "
                  "finer mesh of this size [m] and fit again (docs/CALIBRATION.md)");
  app->add_option("--size", o->size, "picture size WIDTHxHEIGHT in pixels")->capture_default_str();
  return {app, [o]()
          {
            Config c = o->case_file.empty() ? Config() : load_case(o->case_file, o->sets);
            if (o->case_file.empty())
              c = with_overrides(c, o->sets);
            c.validate();
            insert_petsc_options(c, o->petsc_options);
            if (o->max_evals < 1)
              throw InputError(fmt::format("--max-evals = {} must be >= 1", o->max_evals));
            const double h = c.number("geometry.mesh_size");
            if (o->correction_mesh_size != 0
                && !(o->correction_mesh_size > 0 && o->correction_mesh_size < h))
              throw InputError(fmt::format("--correction-mesh-size = {} must be in (0, {}) m: "
                                           "finer than the fit's geometry.mesh_size",
                                           o->correction_mesh_size, h));
            if (o->correction_mesh_size > 0)
            {
              Config fine = c; // the schema's range for mesh sizes, named in the message
              fine.set("geometry.mesh_size", o->correction_mesh_size);
              fine.validate();
            }
            {
              // Checked here, before a long fit (render.py checks it again).
              int w = 0, ht = 0;
              char rest = 0;
              if (std::sscanf(o->size.c_str(), "%dx%d%c", &w, &ht, &rest) != 2 || w < 100
                  || w > 8000 || ht < 100 || ht > 8000)
                throw InputError(fmt::format("--size '{}' must be WIDTHxHEIGHT with both in [100, "
                                             "8000] pixels, e.g. 800x600",
                                             o->size));
            }
            check_picture_tools(MPI_COMM_WORLD); // before a long fit, not after it
            const std::string default_out = "results/" + c.text("case.name") + "_calibrated";
            const std::vector<std::string> inputs = {o->measurements, o->case_file};
            // Every input is read and checked before the output folder is claimed.
            const auto doc = calibration::read_json_file(o->measurements, "measurements file");
            if (calibration::is_recording(doc))
            {
              // 3D surface points: the point-to-skin fit of `diagnose`, without discovery.
              const auto rec = calibration::parse_recording(doc, o->measurements);
              const auto out = claim_output(o->out, default_out, inputs);
              calibration::DiagnoseOptions d;
              d.fit = o->fit;
              d.discover = false;
              OutputDir dir(out, MPI_COMM_WORLD);
              const auto res = calibration::diagnose(rec, c, d, MPI_COMM_WORLD);
              calibration::write_diagnosis(dir.path(), res, rec, MPI_COMM_WORLD);
              write_text(dir.path() / "calibrated.toml", res.final_fit.config.to_toml(), MPI_COMM_WORLD);
              dir.commit();
              if (log::is_root())
                std::cout << calibration::report_text(res, rec) << "results written to " << out.path().string()
                          << "/ (calibrated.toml, diagnosis.json, residual maps)\n";
              return 0;
            }
            const auto data = calibration::parse_measurements(doc, o->measurements);
            const auto fit = calibration::parse_fit(o->fit, c);
            calibration::check_algorithm(o->algorithm);
            calibration::CalibrateOptions co;
            co.optimizer.algorithm = o->algorithm;
            co.optimizer.max_evals = o->max_evals;
            co.checkpoint = claim_file(o->checkpoint.empty()
                                           ? normalise_path(output_name(o->out, default_out)).string()
                                                 + ".checkpoint.json"
                                           : o->checkpoint,
                                       inputs, "the checkpoint");
            const auto out = claim_output(o->out, default_out, inputs);
            co.resume = o->resume;
            co.measurements_source = o->measurements;
            co.morph = !o->remesh;
            co.correction_mesh_size = o->correction_mesh_size;
            log::info("calibrating [{}] with {} against {} measurements in {} postures", o->fit,
                      o->algorithm, data.items.size(), data.postures.size());
            const auto res = calibration::calibrate(c, data, fit, co, MPI_COMM_WORLD);
            calibration::write_calibration(res, out, MPI_COMM_WORLD, {true, o->size});
            if (log::is_root())
            {
              std::cout << calibration::calibration_table(res.report);
              std::cout << "results written to " << out.path().string()
                        << "/ (calibrated.toml for `breastsim simulate`, report.json, "
                           "misfit_history.png, measurements.png, view_<posture>.png)\n";
            }
            return 0;
          }};
}

Command add_measure_command(CLI::App& root)
{
  struct Options
  {
    std::string case_file, out;
    std::vector<std::string> sets;
    double mesh_size = 0, noise = 5e-4, sigma = 0;
    unsigned seed = 1;
  };
  auto o = std::make_shared<Options>();
  auto* app = root.add_subcommand("measure", "synthetic measurements of a case (forward model on "
                                             "a finer mesh plus Gaussian noise), in the "
                                             "calibrate input format");
  app->add_option("case", o->case_file, "case file (TOML) holding the true parameters")->required();
  app->add_option("--out", o->out, "measurement file to write (JSON)")->required();
  app->add_option("--set", o->sets, "override a case key (repeatable)");
  app->add_option("--mesh-size", o->mesh_size, "mesh size of the truth [m] (default: half the "
                                               "case's geometry.mesh_size)");
  app->add_option("--noise", o->noise, "standard deviation of the added noise [m]")->capture_default_str();
  app->add_option("--sigma", o->sigma, "sigma written into the file [m] (default: --noise, or "
                                       "0.5 mm without noise)");
  app->add_option("--seed", o->seed, "random seed of the noise")->capture_default_str();
  return {app, [o]()
          {
            Config c = load_case(o->case_file, o->sets);
            c.set("geometry.mesh_size",
                  o->mesh_size > 0 ? o->mesh_size : 0.5 * c.number("geometry.mesh_size"));
            c.validate();
            calibration::SyntheticOptions so;
            so.noise = o->noise;
            so.sigma = o->sigma > 0 ? o->sigma : (o->noise > 0 ? o->noise : 5e-4);
            so.seed = o->seed;
            const auto file = claim_file(o->out, {o->case_file}, "the measurement file");
            const auto doc = calibration::synthetic_measurements(c, so, MPI_COMM_WORLD);
            write_owned_json(file, doc, MPI_COMM_WORLD);
            if (log::is_root())
              std::cout << "measurements written to " << o->out << "\n";
            return 0;
          }};
}
} // namespace breastsim::cli
