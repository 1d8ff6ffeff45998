// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Rank-0 logging on top of spdlog. Quiet mode raises the level to warnings.
// Progress: at the default level, debug messages (load steps, Newton
// iterations) are shown in place on one status line when stderr is a terminal.
#include <cstdio>
#include <mpi.h>
#include <spdlog/spdlog.h>
#include <string>
#include <unistd.h>

namespace breastsim::log
{
/// True on MPI rank 0 of MPI_COMM_WORLD.
inline bool is_root()
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank == 0;
}

/// True when the status line is shown: stderr is a terminal, level info.
inline bool progress_enabled()
{
  static const bool tty = isatty(STDERR_FILENO) == 1;
  return tty && spdlog::get_level() == spdlog::level::info;
}

inline bool& progress_visible()
{
  static bool visible = false;
  return visible;
}

/// Erase the status line (before a normal log line).
inline void clear_progress()
{
  if (progress_visible())
  {
    std::fputs("\r\033[K", stderr);
    progress_visible() = false;
  }
}

/// The current stage shown in front of the status line (the last info message).
inline std::string& progress_stage()
{
  static std::string stage;
  return stage;
}

/// Replace the status line by `stage | text` (rank 0, terminal only).
inline void progress(const std::string& text)
{
  if (!is_root() || !progress_enabled())
    return;
  std::fprintf(stderr, "\r\033[K%.110s", (progress_stage() + " | " + text).c_str());
  std::fflush(stderr);
  progress_visible() = true;
}

template <typename... Args>
void info(fmt::format_string<Args...> f, Args&&... args)
{
  clear_progress();
  if (is_root() && progress_enabled())
    progress_stage() = fmt::vformat(static_cast<fmt::string_view>(f), fmt::make_format_args(args...)).substr(0, 50);
  if (is_root())
    spdlog::info(f, std::forward<Args>(args)...);
}

template <typename... Args>
void warn(fmt::format_string<Args...> f, Args&&... args)
{
  clear_progress();
  if (is_root())
    spdlog::warn(f, std::forward<Args>(args)...);
}

/// A warning from rank 0 of `comm` (e.g. a sub-communicator whose rank 0 is
/// not the world's: a posture group's solver failure, shown where it happens).
template <typename... Args>
void warn_on(MPI_Comm comm, fmt::format_string<Args...> f, Args&&... args)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank != 0)
    return;
  clear_progress();
  spdlog::warn(f, std::forward<Args>(args)...);
}

template <typename... Args>
void debug(fmt::format_string<Args...> f, Args&&... args)
{
  if (spdlog::should_log(spdlog::level::debug))
  {
    if (is_root())
      spdlog::debug(f, std::forward<Args>(args)...);
  }
  else if (progress_enabled())
    progress(fmt::format(f, std::forward<Args>(args)...));
}
} // namespace breastsim::log
