#include "case_groups.hpp"
#include "errors.hpp"
#include <fmt/format.h>

namespace breastsim
{
CaseGroups::CaseGroups(MPI_Comm comm, int ranks_per_case, const std::string& option) : _world(comm)
{
  int size, rank;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  const int k = ranks_per_case == 0 ? size : ranks_per_case;
  if (k < 1 || k > size || size % k != 0)
    throw InputError(fmt::format("{} = {} is out of range: allowed 0 (all ranks on one solve) or a "
                                 "divisor of the {} ranks",
                                 option, ranks_per_case, size));
  _groups = size / k;
  _group = rank / k;
  MPI_Comm_split(comm, _group, rank, &_sub);
}

CaseGroups::~CaseGroups()
{
  if (_sub != MPI_COMM_NULL)
    MPI_Comm_free(&_sub);
}

std::vector<std::string> CaseGroups::gather(const std::vector<std::string>& mine, std::size_t n) const
{
  // Every rank sends "index\n text" records of the cases it holds (texts non-empty).
  std::string packed;
  for (std::size_t i = 0; i < mine.size() && i < n; ++i)
    if (!mine[i].empty())
      packed += fmt::format("{} {}\n", i, mine[i].size()) + mine[i];
  int size, rank;
  MPI_Comm_size(_world, &size);
  MPI_Comm_rank(_world, &rank);
  const int len = static_cast<int>(packed.size());
  std::vector<int> lens(size), offsets(size, 0);
  MPI_Gather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, 0, _world);
  for (int r = 1; r < size; ++r)
    offsets[r] = offsets[r - 1] + lens[r - 1];
  std::string all(rank == 0 ? offsets.back() + lens.back() : 0, '\0');
  MPI_Gatherv(packed.data(), len, MPI_CHAR, all.data(), lens.data(), offsets.data(), MPI_CHAR, 0, _world);
  std::vector<std::string> out(rank == 0 ? n : 0);
  for (std::size_t pos = 0; pos < all.size();)
  {
    const std::size_t eol = all.find('\n', pos);
    std::size_t index = 0, bytes = 0;
    std::sscanf(all.c_str() + pos, "%zu %zu", &index, &bytes);
    if (index < out.size())
      out[index] = all.substr(eol + 1, bytes);
    pos = eol + 1 + bytes;
  }
  return out;
}
} // namespace breastsim
