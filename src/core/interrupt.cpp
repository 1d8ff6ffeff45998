#include "interrupt.hpp"
#include <algorithm>
#include <csignal>
#include <mutex>
#include <pthread.h>
#include <set>
#include <spawn.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace breastsim::interrupt
{
namespace fs = std::filesystem;
namespace
{
std::mutex g_mutex;
std::vector<fs::path> g_paths; // in registration order; removed newest first
std::set<pid_t> g_children;
bool g_installed = false;

sigset_t stop_signals()
{
  sigset_t s;
  sigemptyset(&s);
  sigaddset(&s, SIGINT);
  sigaddset(&s, SIGTERM);
  return s;
}

/// Terminate the children, remove the registered paths, exit 128 + sig.
[[noreturn]] void stop(int sig)
{
  std::lock_guard<std::mutex> lock(g_mutex); // held to the end: nothing registers meanwhile
  for (pid_t c : g_children)
    kill(c, SIGTERM);
  for (pid_t c : g_children)
    waitpid(c, nullptr, 0);
  for (auto it = g_paths.rbegin(); it != g_paths.rend(); ++it)
    for (int attempt = 0; attempt < 5; ++attempt) // the main thread may still be writing
    {
      std::error_code ec;
      fs::remove_all(*it, ec);
      if (!ec && !fs::exists(fs::symlink_status(*it, ec)))
        break;
    }
  _exit(128 + sig);
}
} // namespace

void install()
{
  if (g_installed)
    return;
  g_installed = true;
  const sigset_t s = stop_signals();
  pthread_sigmask(SIG_BLOCK, &s, nullptr);
  std::thread(
      [s]()
      {
        int sig = 0;
        while (sigwait(&s, &sig) != 0)
          ;
        stop(sig);
      })
      .detach();
}

void register_path(const fs::path& p)
{
  std::lock_guard<std::mutex> lock(g_mutex);
  g_paths.push_back(p);
}

void unregister_path(const fs::path& p)
{
  std::lock_guard<std::mutex> lock(g_mutex);
  g_paths.erase(std::remove(g_paths.begin(), g_paths.end(), p), g_paths.end());
}

int run_child(const std::vector<std::string>& argv)
{
  std::vector<char*> args;
  for (const auto& a : argv)
    args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none); // the child handles SIGINT/SIGTERM itself
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
  pid_t pid = 0;
  int rc;
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    rc = posix_spawnp(&pid, args[0], nullptr, &attr, args.data(), environ);
    if (rc == 0)
      g_children.insert(pid);
  }
  posix_spawnattr_destroy(&attr);
  if (rc != 0)
    return -1;
  int status = 0;
  const bool waited = waitpid(pid, &status, 0) == pid;
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    g_children.erase(pid);
  }
  if (!waited || !WIFEXITED(status))
    return -1;
  return WEXITSTATUS(status);
}
} // namespace breastsim::interrupt
