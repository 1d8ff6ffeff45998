// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Work that only rank 0 does (file-system changes), with its outcome shared:
// on_root() runs `f` on rank 0 and every rank then throws what it threw;
// broadcast() gives every rank rank 0's string.
#include "errors.hpp"
#include <mpi.h>
#include <stdexcept>
#include <string>

namespace breastsim
{
inline int rank_of(MPI_Comm comm)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  return rank;
}

inline void broadcast(std::string& s, MPI_Comm comm)
{
  int n = static_cast<int>(s.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, comm);
  s.resize(n);
  MPI_Bcast(s.data(), n, MPI_CHAR, 0, comm);
}

/// Collective. Run `f` on rank 0; an InputError or other exception it throws
/// is thrown again, as InputError or std::runtime_error, on every rank.
template <typename F>
void on_root(MPI_Comm comm, F&& f)
{
  std::string error;
  int input = 0;
  if (rank_of(comm) == 0)
  {
    try
    {
      f();
    }
    catch (const InputError& e)
    {
      error = e.what();
      input = 1;
    }
    catch (const std::exception& e)
    {
      error = e.what();
    }
  }
  broadcast(error, comm);
  MPI_Bcast(&input, 1, MPI_INT, 0, comm);
  if (!error.empty() && input)
    throw InputError(error);
  if (!error.empty())
    throw std::runtime_error(error);
}
} // namespace breastsim
