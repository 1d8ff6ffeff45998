#include "calibration_plots.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "viewer.hpp"
#include <spawn.h>
#include <sys/wait.h>
#include <vector>

extern char** environ;

namespace breastsim::calibration
{
namespace
{
/// Run `argv` (no shell) on rank 0 and share its exit code (-1: could not run).
int run_on_root(const std::vector<std::string>& argv, MPI_Comm comm)
{
  int rank, code = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
  {
    std::vector<char*> args;
    for (const auto& a : argv)
      args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid;
    int status = 0;
    if (posix_spawn(&pid, args[0], nullptr, nullptr, args.data(), environ) != 0
        || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status))
      code = -1;
    else
      code = WEXITSTATUS(status);
  }
  MPI_Bcast(&code, 1, MPI_INT, 0, comm);
  return code;
}
} // namespace

void render_calibration_pictures(const std::filesystem::path& dir, const std::string& size,
                                 MPI_Comm comm)
{
  const std::string script = (viewer_dir() / "calibration_plots.py").string();
  log::info("plotting the calibration ({} px)", size);
  const int code = run_on_root({viewer_python(), script, dir.string(), "--size", size}, comm);
  if (code == 3 || code < 0)
    check_picture_tools(comm); // python3 or matplotlib missing: throws with the installation hint
  if (code == 2)
    throw InputError("calibration plots failed (see the message above)");
  if (code != 0)
    throw std::runtime_error("calibration plots (" + script + ") failed with exit code "
                             + std::to_string(code));
  render_pictures(dir, {"", size}, comm);
}
} // namespace breastsim::calibration
