// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim neutral-state CASE.toml --posture standing`: the stress-free
// neutral state of the case's shape, recorded in a loaded posture.
#include "case_options.hpp"
#include "command.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "neutral_state.hpp"
#include "output_options.hpp"
#include "overrides.hpp"
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace breastsim::cli
{
Command add_neutral_state_command(CLI::App& root)
{
  struct Options
  {
    std::string case_file, posture = "standing";
    double theta = std::numeric_limits<double>::quiet_NaN();
    InverseOptions inverse;
    OutputOption out;
    std::vector<std::string> sets;
  };
  auto o = std::make_shared<Options>();
  auto* app = root.add_subcommand(
      "neutral-state", "the stress-free neutral state of a shape recorded in a loaded posture "
                       "(inverse elastostatics); writes its mesh and a case that uses it");
  app->add_option("case", o->case_file, "case file: its geometry (geometry.mesh_file, or the cap) is "
                                        "the loaded shape, its material and gravity the load")->required();
  app->add_option("--set", o->sets, "override a case key (repeatable)")->allow_extra_args(false);
  app->add_option("--posture", o->posture, "posture the shape was recorded in")
      ->check(CLI::IsMember({"standing", "supine", "all_fours", "prone"}))->capture_default_str();
  app->add_option("--theta", o->theta, "chest angle theta [deg] instead of --posture, in [-180, 180]");
  app->add_option("--tolerance", o->inverse.tolerance, "largest node mismatch accepted [m], in [1e-9, 1e-3]")
      ->capture_default_str();
  app->add_option("--max-iterations", o->inverse.max_iterations, "in [1, 500]")->capture_default_str();
  add_output_option(app, o->out, "output folder (default results/<case.name>-neutral); replaced on success");
  return {app, [o]()
          {
            if (!(o->inverse.tolerance >= 1e-9 && o->inverse.tolerance <= 1e-3))
              throw InputError(fmt::format("--tolerance = {} is out of range: allowed [1e-9, 1e-3] m",
                                           o->inverse.tolerance));
            if (o->inverse.max_iterations < 1 || o->inverse.max_iterations > 500)
              throw InputError(fmt::format("--max-iterations = {} is out of range: allowed [1, 500]",
                                           o->inverse.max_iterations));
            if (!std::isnan(o->theta) && !(o->theta >= -180 && o->theta <= 180))
              throw InputError(fmt::format("--theta = {} is out of range: allowed [-180, 180] deg", o->theta));
            const Config c = load_case(o->case_file, o->sets);
            const Posture p = std::isnan(o->theta) ? named_posture(o->posture) : posture_from_angle(o->theta);
            const auto out = claim_output(o->out, "results/" + CaseOptions::from(c).name + "-neutral",
                                          {o->case_file});
            const NeutralStateResult r = neutral_state(c, p, o->inverse, out, MPI_COMM_WORLD);
            if (log::is_root())
            {
              const OutputOptions output = OutputOptions::from(c);
              std::string files = "reference.msh, case.reference.toml, summary.json";
              for (const auto& [on, ext] : {std::pair{output.xdmf, ".xdmf"}, std::pair{output.vtk, ".pvd"}})
                if (on)
                  files += ", neutral_" + p.name + ext;
              std::cout << neutral_state_table(r) << "results written to " << out.path().string()
                        << "/ (" << files << ")\n";
            }
            return 0;
          }};
}
} // namespace breastsim::cli
