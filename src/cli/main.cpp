// SPDX-License-Identifier: LGPL-3.0-or-later
// breastsim command-line interface: a thin layer over the library. Each
// subcommand is in its own file (see command.hpp) and listed once below.
#include "errors.hpp"
#include "interrupt.hpp"
#include "log.hpp"
#include "output_target.hpp"
#include "petsc.hpp"
#include "command.hpp"
#include "strings.hpp"
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <dolfinx/common/log.h>
#include <dolfinx/common/timing.h>
#include <functional>
#include <iostream>

namespace
{
/// The first argument that is not an option, if it names no subcommand.
std::string unknown_subcommand(int argc, char** argv, const CLI::App& app)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (!a.empty() && a[0] == '-')
      continue;
    for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; }))
      if (sub->get_name() == a)
        return "";
    return a;
  }
  return "";
}

/// A message for the terminal: every run of more than 300 non-blank bytes
/// (a pasted value, a file's contents) shortened.
std::string bounded(const std::string& message)
{
  std::string out, word;
  auto flush = [&]
  {
    out += breastsim::shorten(word, word.size() > 300 ? 80 : 300);
    word.clear();
  };
  for (char ch : message)
  {
    if (ch == ' ' || ch == '\n')
    {
      flush();
      out += ch;
    }
    else
      word += ch;
  }
  flush();
  return out;
}

/// Why this process cannot start MPI/PETSc cleanly, or "" if it can: a
/// working directory that was deleted, a $TMPDIR that does not exist (OpenMPI
/// would create it).
std::string environment_problem()
{
  std::error_code ec;
  (void)std::filesystem::current_path(ec);
  if (ec)
    return "the working directory cannot be read (" + ec.message()
           + "; was it deleted?): cd to an existing folder";
  if (const char* t = std::getenv("TMPDIR"); t && *t && !std::filesystem::is_directory(t, ec))
    return "TMPDIR = '" + breastsim::shorten(t) + "' is not an existing folder: create it or unset TMPDIR";
  return "";
}

/// Flush standard output; false (with a message) if it cannot be written
/// (a full device). Standard output then goes to /dev/null, so that nothing
/// later (PETSc's finalisation) reports the same failure again.
bool stdout_ok()
{
  std::cout.flush();
  const bool ok = std::cout.good() && std::fflush(stdout) == 0 && !std::ferror(stdout);
  if (!ok)
  {
    const int err = errno;
    std::cerr << "breastsim: error: cannot write to standard output: " << std::strerror(err) << "\n";
    std::cout.clear();
    std::clearerr(stdout);
    if (!std::freopen("/dev/null", "w", stdout))
      std::cerr << "breastsim: error: cannot redirect standard output\n";
  }
  return ok;
}

/// Run the parsed subcommand: its exit code, or that of its error (input 2,
/// solve 3, anything else 1). With -v, dolfinx's timing table at the end.
int run_command(const std::vector<breastsim::cli::Command>& commands)
{
  using namespace breastsim;
  int code = 0;
  try
  {
    for (const auto& c : commands)
      if (c.app->parsed())
        code = c.run();
    // -v: dolfinx's timing table (collective: only when every rank finished)
    if (spdlog::should_log(spdlog::level::debug) && code == 0)
      dolfinx::list_timings(MPI_COMM_WORLD, {dolfinx::TimingType::wall});
  }
  catch (const InputError& e)
  {
    if (log::is_root())
      std::cerr << "breastsim: input error: " << bounded(e.what()) << "\n";
    code = 2;
  }
  catch (const SolveError& e)
  {
    if (log::is_root())
      std::cerr << "breastsim: solve failed: " << bounded(e.what()) << "\n";
    code = 3;
  }
  catch (const std::exception& e)
  {
    if (log::is_root())
      std::cerr << "breastsim: error: " << bounded(e.what()) << "\n";
    code = 1;
  }
  return code;
}

/// Parse the command line: -1 to go on, else the exit code (0 after --help,
/// 2 for an unknown subcommand or any other command-line error).
int parse_command_line(int argc, char** argv, CLI::App& app,
                       const std::vector<breastsim::cli::Command>& commands)
{
  using namespace breastsim;
  if (const std::string sub = unknown_subcommand(argc, argv, app); !sub.empty())
  {
    std::string names;
    std::vector<std::string> all;
    for (const auto& c : commands)
    {
      names += (names.empty() ? "" : ", ") + c.app->get_name();
      all.push_back(c.app->get_name());
    }
    const std::string guess = closest_match(sub, all);
    std::cerr << "breastsim: unknown subcommand '" << shorten(sub) << "'"
              << (guess.empty() ? "" : ": did you mean '" + guess + "'?") << " (one of: " << names
              << ")\n";
    return 2;
  }
  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    if (e.get_exit_code() == 0)
      return app.exit(e); // --help
    // Every command-line error is bad input, said as breastsim says it.
    std::cerr << "breastsim: input error: " << bounded(e.what()) << " (see `breastsim "
              << (app.get_subcommands().empty() ? std::string("--help")
                                                : app.get_subcommands().front()->get_name() + " --help")
              << "`)\n";
    return 2;
  }

  return -1;
}

/// A checked PETSc call outside any command (initialise, finalise): false,
/// with the error printed, if it fails.
bool petsc_ok(const std::function<void()>& checked_call)
{
  try
  {
    checked_call();
    return true;
  }
  catch (const breastsim::PetscCallError& e)
  {
    std::cerr << "breastsim: error: " << bounded(e.what()) << "\n";
    return false;
  }
}
} // namespace

int main(int argc, char** argv)
{
  using namespace breastsim;
  interrupt::install(); // first: the signal mask is inherited by every later thread
  set_command_line(argc, argv);
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
      cli::add_serve_command(app),
      cli::add_neutral_state_command(app),
      cli::add_scan_model_command(app),
      cli::add_synthetic_patient_command(app),
      cli::add_scan_calibrate_command(app),
      cli::add_patient_command(app),
      cli::add_plan_command(app),
  };

  if (const int code = parse_command_line(argc, argv, app, commands); code >= 0)
    return code;
  if (const std::string problem = environment_problem(); !problem.empty())
  {
    std::cerr << "breastsim: error: " << problem << "\n";
    return 1;
  }
  // Run alone (not under mpirun), OpenMPI needs no helper daemon (orted).
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  // OpenMPI's ob1 messaging (shared memory, TCP) instead of probing UCX:
  // start-up 0.45 -> 0.23 s on one machine. Every rank sets the same, and a
  // value already in the environment (e.g. pml ucx on an InfiniBand
  // cluster) is kept.
  setenv("OMPI_MCA_pml", "ob1", 0);
  if (!petsc_ok([] { PETSC_CHECK(PetscInitializeNoArguments()); }))
    return 1;
  // PETSc's handlers would turn SIGPIPE and friends into an MPI abort (exit
  // 59); breastsim's own handling (interrupt.hpp) takes their place.
  if (!petsc_ok([] { PETSC_CHECK(PetscPopSignalHandler()); }))
    return 1;
  interrupt::stop_on_broken_pipe();
  loguru::g_stderr_verbosity = loguru::Verbosity_WARNING; // dolfinx's own log
  spdlog::set_level(quiet ? spdlog::level::warn
                          : (verbose ? spdlog::level::debug : spdlog::level::info));
  spdlog::set_pattern("[%H:%M:%S] %v");
  int code = run_command(commands);
  if (!stdout_ok() && code == 0)
    code = 1;
  if (!petsc_ok([] { PETSC_CHECK(PetscFinalize()); }))
    return code == 0 ? 1 : code;
  return code;
}
