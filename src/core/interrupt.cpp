// SPDX-License-Identifier: LGPL-3.0-or-later
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
pthread_t g_signal_thread;

/// The signals the signal thread waits for: blocked in every thread.
sigset_t stop_signals()
{
  sigset_t s;
  sigemptyset(&s);
  sigaddset(&s, SIGINT);
  sigaddset(&s, SIGTERM);
  sigaddset(&s, SIGHUP);
  return s;
}

/// SIGPIPE is raised in the thread that wrote to the closed pipe, so it is
/// not blocked there; this handler forwards it to the signal thread.
void forward_broken_pipe(int) { pthread_kill(g_signal_thread, SIGPIPE); }

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
  std::signal(SIGXFSZ, SIG_IGN); // a file-size limit fails the write (EFBIG) instead of killing
  std::thread signal_thread(
      [s]()
      {
        sigset_t wait_for = s;
        sigaddset(&wait_for, SIGPIPE); // forwarded here by forward_broken_pipe
        pthread_sigmask(SIG_BLOCK, &wait_for, nullptr);
        int sig = 0;
        while (sigwait(&wait_for, &sig) != 0)
          ;
        stop(sig);
      });
  g_signal_thread = signal_thread.native_handle();
  signal_thread.detach();
}

void stop_on_broken_pipe()
{
  struct sigaction a{};
  a.sa_handler = forward_broken_pipe;
  sigemptyset(&a.sa_mask);
  a.sa_flags = SA_RESTART;
  sigaction(SIGPIPE, &a, nullptr);
}

void ignore_broken_pipe() { std::signal(SIGPIPE, SIG_IGN); }

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
  sigset_t defaults; // and gets the default action of the signals this process ignores
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  sigaddset(&defaults, SIGXFSZ);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
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
