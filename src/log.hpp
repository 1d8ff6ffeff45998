#pragma once
// Rank-0 logging on top of spdlog. Quiet mode raises the level to warnings.
#include <mpi.h>
#include <spdlog/spdlog.h>

namespace breastsim::log
{
/// True on MPI rank 0 of MPI_COMM_WORLD.
inline bool is_root()
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank == 0;
}

template <typename... Args>
void info(fmt::format_string<Args...> f, Args&&... args)
{
  if (is_root())
    spdlog::info(f, std::forward<Args>(args)...);
}

template <typename... Args>
void warn(fmt::format_string<Args...> f, Args&&... args)
{
  if (is_root())
    spdlog::warn(f, std::forward<Args>(args)...);
}

template <typename... Args>
void debug(fmt::format_string<Args...> f, Args&&... args)
{
  if (is_root())
    spdlog::debug(f, std::forward<Args>(args)...);
}
} // namespace breastsim::log
