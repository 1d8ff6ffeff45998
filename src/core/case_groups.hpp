#pragma once
// Independent solves over MPI sub-communicators: the ranks of a communicator
// split into groups of `ranks_per_case` consecutive ranks, each group running
// its share of the cases (case i on group i mod groups) as one solve.
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

private:
  MPI_Comm _world, _sub = MPI_COMM_NULL;
  int _group = 0, _groups = 1;
};
} // namespace breastsim
