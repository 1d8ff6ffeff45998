// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim measure CASE.toml`: synthetic measurements from the forward model.
#include "case_options.hpp"
#include "command.hpp"
#include "log.hpp"
#include "output.hpp"
#include "overrides.hpp"
#include "synthetic.hpp"
#include <iostream>
#include <memory>

namespace breastsim::cli
{
Command add_measure_command(CLI::App& root)
{
  struct Options
  {
    std::string case_file, out;
    std::vector<std::string> sets;
    calibration::MeasureRequest r;
  };
  auto o = std::make_shared<Options>();
  auto* app = root.add_subcommand("measure", "synthetic measurements of a case (forward model on "
                                             "a finer mesh plus Gaussian noise), in the "
                                             "calibrate input format");
  app->add_option("case", o->case_file, "case file (TOML) holding the true parameters")->required();
  app->add_option("--out", o->out, "measurement file to write (JSON)")->required();
  app->add_option("--set", o->sets, "override a case key (repeatable)");
  app->add_option("--mesh-size", o->r.mesh_size, "mesh size of the truth [m] (default: half the "
                                                 "case's geometry.mesh_size)");
  app->add_option("--noise", o->r.noise, "standard deviation of the added noise [m]")->capture_default_str();
  app->add_option("--sigma", o->r.sigma, "sigma written into the file [m] (default: --noise, or "
                                         "0.5 mm without noise)");
  app->add_option("--seed", o->r.seed, "random seed of the noise")->capture_default_str();
  return {app, [o]()
          {
            const Config truth = calibration::measure_truth(load_case(o->case_file, o->sets), o->r);
            const auto file = claim_file(o->out, {o->case_file}, "the measurement file");
            const auto doc = calibration::synthetic_measurements(truth, calibration::synthetic_options(o->r),
                                                                 MPI_COMM_WORLD);
            write_owned_json(file, doc, MPI_COMM_WORLD);
            if (log::is_root())
              std::cout << "measurements written to " << o->out << "\n";
            return 0;
          }};
}
} // namespace breastsim::cli
