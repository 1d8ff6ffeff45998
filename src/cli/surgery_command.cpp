// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim surgery CASE.toml`: incision, sutures, final neutral state and
// post-operative postures.
#include "log.hpp"
#include "case_options.hpp"
#include "fit_parameters.hpp"
#include <fmt/format.h>
#include "full_breast_surgery.hpp"
#include "surgery.hpp"
#include "command.hpp"
#include "overrides.hpp"
#include <iostream>
#include <memory>

namespace breastsim::cli
{
namespace
{
/// The resected tissue's weight, as the planning app reports it:
/// resected volume (the whole breast) times the tissue's density.
std::string resected_weight_line(const Config& c, double resected_volume_m3)
{
  const double rho = c.number(calibration::fit_alias("rho").key);
  return fmt::format("resected weight {:.0f} g (this breast; {:.1f} cm^3 at {:.0f} kg/m^3)\n",
                     1e3 * resected_volume_m3 * rho, 1e6 * resected_volume_m3, rho);
}
} // namespace

Command add_surgery_command(CLI::App& root)
{
  struct Options
  {
    std::string case_file, petsc_options;
    OutputOption out;
    std::vector<std::string> sets;
  };
  auto o = std::make_shared<Options>();
  auto* app = root.add_subcommand(
      "surgery", "breast reduction: incision (a, s, h, d), sutures, final neutral state, post-op postures");
  app->add_option("case", o->case_file, "case file with [incision] (a_deg, s, h, d); see `breastsim keys`")
      ->required();
  app->add_option("--set", o->sets, "override a case key, e.g. --set incision.a_deg=35 (repeatable)")
      ->allow_extra_args(false);
  add_output_option(app, o->out, "output folder (default results/<case.name>-surgery); replaced on success");
  app->add_option("--petsc-options", o->petsc_options, "PETSc options passed through");
  return {app, [o]()
          {
            Config c = load_case(o->case_file, o->sets);
            insert_petsc_options(c, o->petsc_options);
            const auto out = claim_output(o->out, "results/" + CaseOptions::from(c).name + "-surgery",
                                          {o->case_file});
            if (is_full_breast_case(c)) // geometry.mesh_file: the user's full breast
            {
              auto r = full_breast_surgery(c, out, MPI_COMM_WORLD);
              if (log::is_root())
                std::cout << surgery_table(r.base) << resected_weight_line(c, r.base.resected_volume)
                          << fmt::format("largest gaps: keel faces {:.4f} mm, P2 face to the chest {:.4f} mm\n",
                                         1e3 * r.gap_tissue, 1e3 * r.gap_chest)
                          << "results written to " << out.path().string() << "/\n"
                          << pictures_hint(c, out.path());
              return 0;
            }
            auto r = surgery(c, out, MPI_COMM_WORLD);
            if (log::is_root())
            {
              if (spdlog::should_log(spdlog::level::debug)) // -v
                std::cout << newton_tables(r.pre, "pre-operative: ")
                          << newton_tables(r.post, "post-operative: ");
              std::cout << surgery_table(r) << resected_weight_line(c, r.resected_volume) << "results written to " << out.path().string() << "/\n"
                        << pictures_hint(c, out.path());
            }
            return 0;
          }};
}
} // namespace breastsim::cli
