// breastsim command-line interface: a thin layer over the library.
#include "../config.hpp"
#include "../errors.hpp"
#include "../log.hpp"
#include "../simulate.hpp"
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <dolfinx/common/log.h>
#include <petscsys.h>

namespace
{
/// Parse "key=value" overrides into the configuration.
void apply_overrides(breastsim::Config& c, const std::vector<std::string>& sets)
{
  for (const auto& s : sets)
  {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw breastsim::InputError("--set expects key=value, got '" + s + "'");
    c.set_text(s.substr(0, eq), s.substr(eq + 1));
  }
  c.validate();
}

int run_simulate(const std::string& case_file, const std::vector<std::string>& sets,
                 std::string out, const std::string& petsc_options)
{
  breastsim::Config c = breastsim::Config::from_file(case_file);
  apply_overrides(c, sets);
  const std::string opts = c.text("solver.petsc_options") + " " + petsc_options;
  PetscOptionsInsertString(nullptr, opts.c_str());
  if (out.empty())
    out = "results/" + c.text("case.name");
  auto res = breastsim::simulate(c, out, MPI_COMM_WORLD);
  if (breastsim::log::is_root())
  {
    std::cout << breastsim::observables_table(res.postures);
    std::cout << "results written to " << out << "/ (summary.json, case.resolved.toml, XDMF)\n";
  }
  return 0;
}
} // namespace

int main(int argc, char** argv)
{
  CLI::App app{"breastsim: simulation of breast reduction surgery (neo-Hookean tissue, skin "
               "membrane, Chassaignac springs, gravity in any posture)"};
  app.require_subcommand(1);
  bool quiet = false, verbose = false;
  app.add_flag("-q,--quiet", quiet, "only warnings and errors");
  app.add_flag("-v,--verbose", verbose, "log every Newton iteration");

  auto* sim = app.add_subcommand("simulate", "solve the case in each requested posture");
  std::string case_file, out, petsc_options;
  std::vector<std::string> sets;
  sim->add_option("case", case_file, "case file (TOML, SI units; see `breastsim keys`)")->required();
  sim->add_option("--set", sets, "override a case key, e.g. --set tissue.mu=800 (repeatable)");
  sim->add_option("--out", out, "output folder (default results/<case.name>); replaced on success");
  sim->add_option("--petsc-options", petsc_options,
                  "PETSc options passed through, e.g. \"-ksp_type gmres -pc_type gamg\"");

  auto* keys = app.add_subcommand("keys", "print every case-file key (Markdown table)");

  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    return app.exit(e);
  }

  PetscInitializeNoArguments();
  loguru::g_stderr_verbosity = loguru::Verbosity_WARNING; // dolfinx's own log
  spdlog::set_level(quiet ? spdlog::level::warn
                          : (verbose ? spdlog::level::debug : spdlog::level::info));
  spdlog::set_pattern("[%H:%M:%S] %v");
  int code = 0;
  try
  {
    if (*keys)
    {
      if (breastsim::log::is_root())
        std::cout << breastsim::schema_markdown();
    }
    else if (*sim)
      code = run_simulate(case_file, sets, out, petsc_options);
  }
  catch (const breastsim::InputError& e)
  {
    if (breastsim::log::is_root())
      std::cerr << "breastsim: input error: " << e.what() << "\n";
    code = 2;
  }
  catch (const breastsim::SolveError& e)
  {
    if (breastsim::log::is_root())
      std::cerr << "breastsim: solve failed: " << e.what() << "\n";
    code = 3;
  }
  catch (const std::exception& e)
  {
    if (breastsim::log::is_root())
      std::cerr << "breastsim: error: " << e.what() << "\n";
    code = 1;
  }
  PetscFinalize();
  return code;
}
