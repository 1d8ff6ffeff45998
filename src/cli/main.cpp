// breastsim command-line interface: a thin layer over the library. Each
// subcommand is in its own file (see command.hpp) and listed once below.
#include "../errors.hpp"
#include "../log.hpp"
#include "command.hpp"
#include <dolfinx/common/log.h>
#include <iostream>
#include <petscsys.h>

int main(int argc, char** argv)
{
  using namespace breastsim;
  CLI::App app{"breastsim: simulation of breast reduction surgery (neo-Hookean tissue, skin "
               "membrane, Chassaignac springs, gravity in any posture)"};
  app.require_subcommand(1);
  bool quiet = false, verbose = false;
  app.add_flag("-q,--quiet", quiet, "only warnings and errors");
  app.add_flag("-v,--verbose", verbose, "log every Newton iteration");

  const std::vector<cli::Command> commands = {
      cli::add_simulate_command(app),
      cli::add_keys_command(app),
      cli::add_calibrate_command(app), cli::add_measure_command(app),
      cli::add_view_command(app),
      cli::add_surgery_command(app),
      cli::add_sweep_command(app),
      cli::add_converge_command(app),
      cli::add_record_command(app),
      cli::add_diagnose_command(app),
  };

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
    for (const auto& c : commands)
      if (c.app->parsed())
        code = c.run();
  }
  catch (const InputError& e)
  {
    if (log::is_root())
      std::cerr << "breastsim: input error: " << e.what() << "\n";
    code = 2;
  }
  catch (const SolveError& e)
  {
    if (log::is_root())
      std::cerr << "breastsim: solve failed: " << e.what() << "\n";
    code = 3;
  }
  catch (const std::exception& e)
  {
    if (log::is_root())
      std::cerr << "breastsim: error: " << e.what() << "\n";
    code = 1;
  }
  PetscFinalize();
  return code;
}
