// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim record CASE.toml --out REC.json [--hidden NAME --value Q]`:
// a synthetic 3D surface recording of the case with one hidden candidate
// physics (or none), on a finer mesh, with noise.
#include "log.hpp"
#include "output.hpp"
#include "candidates.hpp"
#include "command.hpp"
#include "overrides.hpp"
#include "recording_generator.hpp"
#include <iostream>
#include <memory>

namespace breastsim::cli
{
Command add_record_command(CLI::App& root)
{
  struct Options
  {
    std::string case_file, out;
    std::vector<std::string> sets;
    diagnosis::RecordingOptions r;
  };
  auto o = std::make_shared<Options>();
  auto* app = root.add_subcommand("record", "synthetic 3D surface recording of a case with a hidden "
                                            "physics term (proof data for `diagnose`)");
  app->add_option("case", o->case_file, "case file (TOML): the current model and its parameters")->required();
  app->add_option("--out", o->out, "recording to write (JSON, breastsim-recording/1)")->required();
  app->add_option("--set", o->sets, "override a case key (repeatable)");
  app->add_option("--hidden", o->r.hidden, "candidate physics switched on in the truth ("
                                               + diagnosis::candidate_names()
                                               + "); default none (a control)");
  app->add_option("--value", o->r.value, "its parameter ("
                                             + diagnosis::candidate_parameters()
                                             + "); default: the candidate's typical value");
  app->add_option("--points", o->r.points, "points per posture")->capture_default_str();
  app->add_option("--noise", o->r.noise, "noise sigma per coordinate [m]")->capture_default_str();
  app->add_option("--seed", o->r.seed, "random seed")->capture_default_str();
  app->add_option("--mesh-size", o->r.mesh_size, "mesh size of the truth [m] (default: the case's "
                                                 "geometry.mesh_size / 1.5)");
  return {app, [o]()
          {
            const Config c = load_case(o->case_file, o->sets);
            const auto file = claim_file(o->out, {o->case_file}, "the recording");
            const auto rec = diagnosis::synthetic_recording(c, o->r, MPI_COMM_WORLD);
            write_owned_json(file, calibration::to_json(rec), MPI_COMM_WORLD);
            if (log::is_root())
              std::cout << "recording written to " << o->out << " (hidden: "
                        << (o->r.hidden.empty() ? "none" : o->r.hidden) << ")\n";
            return 0;
          }};
}
} // namespace breastsim::cli
