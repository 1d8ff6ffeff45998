// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim simulate CASE.toml`: solve a case in each requested posture.
#include "config.hpp"
#include "case_options.hpp"
#include "log.hpp"
#include "simulate.hpp"
#include "command.hpp"
#include "overrides.hpp"
#include <iostream>
#include <memory>
#include <petscsys.h>

namespace breastsim::cli
{
Command add_simulate_command(CLI::App& root)
{
  struct Options
  {
    std::string case_file, petsc_options;
    OutputOption out;
    std::vector<std::string> sets;
  };
  auto o = std::make_shared<Options>();
  auto* app = root.add_subcommand("simulate", "solve the case in each requested posture");
  app->add_option("case", o->case_file, "case file (TOML, SI units; see `breastsim keys`)")->required();
  app->add_option("--set", o->sets, "override a case key, e.g. --set tissue.mu=800 (repeatable)")
      ->allow_extra_args(false);
  add_output_option(app, o->out, "output folder (default results/<case.name>); replaced on success");
  app->add_option("--petsc-options", o->petsc_options,
                  "PETSc options passed through, e.g. \"-ksp_type gmres -pc_type gamg\"");
  return {app, [o]()
          {
            Config c = load_case(o->case_file, o->sets);
            insert_petsc_options(c, o->petsc_options);
            const auto out = claim_output(o->out, "results/" + CaseOptions::from(c).name, {o->case_file});
            auto res = simulate(c, out, MPI_COMM_WORLD);
            if (log::is_root())
            {
              if (spdlog::should_log(spdlog::level::debug)) // -v
                std::cout << newton_tables(res.postures);
              std::cout << observables_table(res.postures);
              std::cout << "results written to " << out.path().string()
                        << "/ (summary.json, case.resolved.toml, XDMF)\n"
                        << pictures_hint(c, out.path());
            }
            return 0;
          }};
}
} // namespace breastsim::cli
