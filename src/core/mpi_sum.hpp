// SPDX-License-Identifier: LGPL-3.0-or-later
// The sum of one number over the ranks of a communicator.
#pragma once
#include <mpi.h>

namespace breastsim
{
/// sum over the ranks of comm of `local` (MPI_Allreduce; collective).
inline double mpi_sum(double local, MPI_Comm comm)
{
  double global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, comm);
  return global;
}
} // namespace breastsim
