// SPDX-License-Identifier: LGPL-3.0-or-later
#include "case_groups.hpp"
#include "errors.hpp"
#include <fmt/format.h>
#include <optional>

namespace breastsim
{
void CaseGroups::check(MPI_Comm comm, int ranks_per_case, const std::string& option)
{
  int size;
  MPI_Comm_size(comm, &size);
  const int k = ranks_per_case == 0 ? size : ranks_per_case;
  if (k < 1 || k > size || size % k != 0)
    throw InputError(fmt::format("{} = {} is out of range: allowed 0 (all ranks on one solve) or a "
                                 "divisor of the {} ranks",
                                 option, ranks_per_case, size));
}

CaseGroups::CaseGroups(MPI_Comm comm, int ranks_per_case, const std::string& option) : _world(comm)
{
  check(comm, ranks_per_case, option);
  int size, rank;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  const int k = ranks_per_case == 0 ? size : ranks_per_case;
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

namespace
{
/// Broadcast a string from `root` of `comm` (length, then bytes).
void broadcast(std::string& s, int root, MPI_Comm comm)
{
  long long len = static_cast<long long>(s.size());
  MPI_Bcast(&len, 1, MPI_LONG_LONG, root, comm);
  s.resize(static_cast<std::size_t>(len));
  MPI_Bcast(s.data(), static_cast<int>(len), MPI_CHAR, root, comm);
}

/// Broadcast a vector of doubles from `root` of `comm`.
void broadcast(std::vector<double>& v, int root, MPI_Comm comm)
{
  long long len = static_cast<long long>(v.size());
  MPI_Bcast(&len, 1, MPI_LONG_LONG, root, comm);
  v.resize(static_cast<std::size_t>(len));
  MPI_Bcast(v.data(), static_cast<int>(len), MPI_DOUBLE, root, comm);
}
} // namespace

std::vector<double> CaseGroups::replicate(const std::function<std::vector<double>()>& f) const
{
  std::vector<double> values;
  std::string failure;
  try
  {
    values = f();
  }
  catch (const SolveError& e)
  {
    failure = e.what();
    if (failure.empty())
      failure = "solve failed";
  }
  if (_groups > 1 && !_in_case)
  {
    broadcast(failure, 0, _world);
    broadcast(values, 0, _world);
  }
  if (!failure.empty())
    throw SolveError(failure);
  return values;
}

std::vector<std::vector<double>> CaseGroups::map(std::size_t n, const CaseFunction& f) const
{
  std::vector<std::vector<double>> values(n);
  std::vector<std::string> failures(n); // SolveError messages ("" = solved)
  for (std::size_t i = 0; i < n; ++i)
    if (runs(i))
    {
      _in_case = true;
      try
      {
        values[i] = f(i);
      }
      catch (const SolveError& e)
      {
        failures[i] = e.what();
        if (failures[i].empty())
          failures[i] = "solve failed";
      }
      catch (...)
      {
        _in_case = false;
        throw;
      }
      _in_case = false;
    }
  if (_groups == 1)
  {
    for (const auto& msg : failures)
      if (!msg.empty())
        throw SolveError(msg);
    return values;
  }
  const int k = [this]
  {
    int size;
    MPI_Comm_size(_world, &size);
    return size / _groups;
  }();
  std::optional<std::string> first_failure;
  for (std::size_t i = 0; i < n; ++i)
  {
    const int root = static_cast<int>(i % _groups) * k; // first rank of case i's group
    broadcast(failures[i], root, _world);
    broadcast(values[i], root, _world);
    if (!failures[i].empty() && !first_failure)
      first_failure = failures[i];
  }
  if (first_failure)
    throw SolveError(*first_failure);
  return values;
}
} // namespace breastsim
