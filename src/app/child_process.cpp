// SPDX-License-Identifier: LGPL-3.0-or-later
#include "child_process.hpp"
#include <csignal>
#include <fcntl.h>
#include <spawn.h>
#include <stdexcept>
#include <string.h>
#include <sys/wait.h>

extern char** environ;

namespace breastsim::app
{
namespace
{
/// Variables of an MPI launcher (Open MPI, PMIx, MPICH): the child must not
/// believe it belongs to the server's MPI job.
bool is_launcher_variable(const std::string& entry)
{
  if (entry.rfind("OMPI_ALLOW_RUN_AS_ROOT", 0) == 0)
    return false;
  for (const char* prefix : {"OMPI_", "PMIX_", "PMI_", "HYDRA_", "MPI_LOCALRANKID", "MPI_LOCALNRANKS"})
    if (entry.rfind(prefix, 0) == 0)
      return true;
  return false;
}
} // namespace

pid_t start_child(const std::vector<std::string>& argv, const std::filesystem::path& output_file)
{
  std::vector<char*> args;
  for (const auto& a : argv)
    args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e)
    if (!is_launcher_variable(*e))
      env_text.emplace_back(*e);
  std::vector<char*> env;
  for (auto& e : env_text)
    env.push_back(e.data());
  env.push_back(nullptr);

  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&files, 1, output_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_NOFOLLOW, 0644);
  posix_spawn_file_actions_adddup2(&files, 1, 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0], &files, &attr, args.data(), env.data());
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&files);
  if (rc != 0)
    throw std::runtime_error("cannot start the job process " + argv[0] + ": " + strerror(rc));
  return pid;
}

std::optional<int> poll_child(pid_t pid)
{
  int status = 0;
  const pid_t r = waitpid(pid, &status, WNOHANG);
  if (r == 0)
    return std::nullopt;
  if (r != pid)
    return -1;
  if (WIFEXITED(status))
    return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

void stop_child(pid_t pid, bool force) { kill(pid, force ? SIGKILL : SIGTERM); }
} // namespace breastsim::app
