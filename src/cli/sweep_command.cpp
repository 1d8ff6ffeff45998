// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim sweep CASE.toml --vary a=25,30,35 --vary h=0.02,0.03`: the
// surgery on a grid of incisions, one table.
#include "errors.hpp"
#include "case_options.hpp"
#include "log.hpp"
#include "sweep.hpp"
#include "command.hpp"
#include "overrides.hpp"
#include <iostream>
#include <memory>
#include <sstream>

namespace breastsim::cli
{
Command add_sweep_command(CLI::App& root)
{
  struct Options
  {
    std::string case_file, petsc_options;
    OutputOption out;
    std::vector<std::string> sets, vary;
    int ranks_per_case = 0;
  };
  auto o = std::make_shared<Options>();
  auto* app = root.add_subcommand("sweep", "run the surgery over a grid of incision parameters");
  app->add_option("case", o->case_file, "case file (see `breastsim keys`)")->required();
  app->add_option("--vary", o->vary,
                  "NAME=v1,v2,... with NAME one of a (deg), s, h, d (m) or any case key (repeatable)")
      ->required()
      ->allow_extra_args(false);
  app->add_option("--set", o->sets, "override a case key (repeatable)")->allow_extra_args(false);
  add_output_option(app, o->out, "output folder (default results/<case.name>-sweep)");
  app->add_option("--petsc-options", o->petsc_options, "PETSc options passed through");
  app->add_option("--ranks-per-case", o->ranks_per_case,
                  "MPI ranks per surgery: the ranks split into groups of this many, each solving "
                  "its share of the grid (0: all ranks on each surgery in turn; must divide the "
                  "number of ranks; with -v the Newton tables of rank 0's group only)")
      ->capture_default_str();
  return {app, [o]()
          {
            Config c = load_case(o->case_file, o->sets);
            insert_petsc_options(c, o->petsc_options);
            SweepGrid grid;
            for (const auto& v : o->vary)
            {
              const auto eq = v.find('=');
              if (eq == std::string::npos || eq == 0)
                throw InputError("--vary expects NAME=v1,v2,..., got '" + v + "'");
              const std::string key = sweep_key(v.substr(0, eq));
              grid.emplace_back(key, sweep_values(c, key, v.substr(eq + 1)));
            }
            check_sweep_request(c, grid);
            const auto out = claim_output(o->out, "results/" + CaseOptions::from(c).name + "-sweep",
                                          {o->case_file});
            auto rows = sweep(c, grid, out, MPI_COMM_WORLD, o->ranks_per_case);
            if (log::is_root() && spdlog::should_log(spdlog::level::debug)) // -v
              for (const auto& row : rows)
                std::cout << newton_tables(row.pre, sweep_label(row) + ", pre-operative: ")
                          << newton_tables(row.post, sweep_label(row) + ", post-operative: ");
            if (log::is_root())
              std::cout << sweep_table(rows) << "results written to " << out.path().string()
                        << "/ (sweep.json, sweep.csv)\n";
            return 0;
          }};
}
} // namespace breastsim::cli
