// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Independent solves over MPI sub-communicators: the ranks of a communicator
// split into groups of `ranks_per_case` consecutive ranks, each group running
// its share of the cases (case i on group i mod groups) as one solve.
#include <functional>
#include <mpi.h>
#include <string>
#include <vector>

namespace breastsim
{
class CaseGroups
{
public:
  /// Collective on `comm`. ranks_per_case 0: one group of all ranks. Throws
  /// InputError naming `option` unless it divides the number of ranks.
  CaseGroups(MPI_Comm comm, int ranks_per_case, const std::string& option);
  ~CaseGroups();
  /// The constructor's check alone (not collective): InputError naming
  /// `option` unless ranks_per_case is 0 or divides the ranks of `comm`.
  static void check(MPI_Comm comm, int ranks_per_case, const std::string& option);
  CaseGroups(const CaseGroups&) = delete;
  CaseGroups& operator=(const CaseGroups&) = delete;

  MPI_Comm comm() const { return _sub; }  ///< this rank's group
  int group() const { return _group; }
  int groups() const { return _groups; }
  bool runs(std::size_t case_index) const { return static_cast<int>(case_index % _groups) == _group; }
  /// Gather to rank 0 of the whole communicator one text per case (given by
  /// the group that ran it, on its first rank; empty elsewhere). Returns all
  /// n texts on rank 0 of the whole communicator, nothing on the others.
  std::vector<std::string> gather(const std::vector<std::string>& mine, std::size_t n) const;
  /// Collective on the whole communicator: values[i] = f(i) for i < n, each
  /// computed by the group that runs case i (collectively on its
  /// sub-communicator) and shared with every rank. A SolveError thrown by
  /// f on any group is thrown on every rank after the exchange.
  using CaseFunction = std::function<std::vector<double>(std::size_t)>;
  std::vector<std::vector<double>> map(std::size_t n, const CaseFunction& f) const;
  /// Collective on the whole communicator: a solve that every group makes
  /// (each keeps its warm starts current), with the result of the first
  /// group taken by all ranks, so that every rank takes the same decisions
  /// (the groups' solver histories differ by the cases each ran). A
  /// SolveError of the first group is thrown on every rank. Inside map's
  /// f (one group's case) it is f alone.
  std::vector<double> replicate(const std::function<std::vector<double>()>& f) const;

private:
  MPI_Comm _world, _sub = MPI_COMM_NULL;
  int _group = 0, _groups = 1;
  mutable bool _in_case = false; ///< inside map's f: no exchange over the whole communicator
};
} // namespace breastsim
