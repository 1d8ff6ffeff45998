// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim calibrate MEASUREMENTS.json`: fit case parameters to measurements.
#include "calibrate_job.hpp"
#include "case_options.hpp"
#include "command.hpp"
#include "log.hpp"
#include "output.hpp"
#include "output_options.hpp"
#include "overrides.hpp"
#include "synthetic.hpp"
#include "viewer.hpp"
#include <iostream>
#include <memory>

namespace breastsim::cli
{
Command add_calibrate_command(CLI::App& root)
{
  struct Options
  {
    calibration::CalibrateRequest r;
    std::string case_file, checkpoint, petsc_options;
    OutputOption out;
    std::vector<std::string> sets;
  };
  auto o = std::make_shared<Options>();
  auto* app = root.add_subcommand(
      "calibrate", "fit tissue/skin/spring parameters and the neutral shape to measurements in "
                   "several postures (docs/CALIBRATION.md)");
  app->add_option("measurements", o->r.data_file, "measurement file (JSON, SI units), or a 3D "
                                                  "surface recording (breastsim-recording/1)")->required();
  app->add_option("--case", o->case_file,
                  "starting case (TOML); its values are the initial guess (default: built-in "
                  "defaults)");
  app->add_option("--set", o->sets, "override a case key, e.g. --set geometry.mesh_size=0.012");
  app->add_option("--fit", o->r.fit, "parameters to fit, comma separated: "
                                         + calibration::fit_alias_names())
      ->capture_default_str();
  app->add_option("--algorithm", o->r.algorithm,
                  "lm (Levenberg-Marquardt with exact sensitivities); bobyqa, sbplx, neldermead "
                  "(derivative-free); lbfgs, slsqp, mma (gradient-based)")
      ->capture_default_str();
  app->add_option("--max-evals", o->r.max_evals, "objective evaluations allowed (in total with "
                                                 "--resume)")
      ->capture_default_str();
  add_output_option(app, o->out, "output folder (default results/<case.name>_calibrated); "
                                 "replaced on success");
  app->add_option("--checkpoint", o->checkpoint, "checkpoint file (default <out>.checkpoint.json)");
  app->add_flag("--resume", o->r.resume, "continue from the checkpoint's best point");
  app->add_option("--petsc-options", o->petsc_options, "PETSc options passed through");
  app->add_flag("--remesh", o->r.remesh, "remesh for every change of R, H instead of morphing the "
                                         "mesh (the misfit is then rough in R, H)");
  app->add_option("--correction-mesh-size", o->r.correction_mesh_size,
                  "after the fit, correct the model by its discretisation error measured on a "
                  "finer mesh of this size [m] and fit again (docs/CALIBRATION.md)");
  app->add_option("--size", o->r.picture_size, "picture size WIDTHxHEIGHT in pixels")
      ->capture_default_str();
  app->add_option("--ranks-per-case", o->r.ranks_per_case,
                  "MPI ranks per forward solve: the ranks split into groups of this many, which "
                  "solve the forward-difference columns (R, H) side by side (0: all ranks on "
                  "each solve; must divide the number of ranks)")
      ->capture_default_str();
  return {app, [o]()
          {
            const Config c = load_case(o->case_file, o->sets);
            insert_petsc_options(c, o->petsc_options);
            calibration::check_calibrate_request(o->r, c);
            // Every input is read and checked before the output folder is claimed.
            const auto job = diagnosis::prepare_calibration(c, o->r);
            if (OutputOptions::from(c).pictures_on())
              check_picture_tools(MPI_COMM_WORLD); // before a long fit, not after it
            const std::string default_out = "results/" + CaseOptions::from(c).name + "_calibrated";
            const std::vector<std::string> inputs = {o->r.data_file, o->case_file};
            std::filesystem::path checkpoint;
            if (job.keeps_checkpoint())
              checkpoint = claim_file(o->checkpoint.empty()
                                          ? normalise_path(output_name(o->out, default_out)).string()
                                                + ".checkpoint.json"
                                          : o->checkpoint,
                                      inputs, "the checkpoint");
            const auto out = claim_output(o->out, default_out, inputs);
            const std::string report = diagnosis::run_calibration(job, out, checkpoint, MPI_COMM_WORLD);
            if (log::is_root())
              std::cout << report << pictures_hint(c, out.path());
            return 0;
          }};
}
} // namespace breastsim::cli
