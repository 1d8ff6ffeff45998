// SPDX-License-Identifier: LGPL-3.0-or-later
#include "observables.hpp"
#include "errors.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace breastsim
{
nlohmann::json to_json(const Observables& o)
{
  return {{"nipple_m", o.nipple},          {"projection_m", o.projection},
          {"z_min_m", o.z_min},            {"z_max_m", o.z_max},
          {"base_perimeter_m", o.base_perimeter}, {"volume_m3", o.volume},
          {"energy_J", o.energy}};
}

namespace
{
/// Rows of N values (reference angle first) from every rank, sorted by the
/// angle, rows of equal angle (ghost copies) dropped.
template <std::size_t N>
std::vector<std::array<double, N>> gather_by_angle(const std::vector<double>& local, MPI_Comm comm)
{
  int nloc = local.size(), size;
  MPI_Comm_size(comm, &size);
  std::vector<int> counts(size), displs(size, 0);
  MPI_Allgather(&nloc, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int i = 1; i < size; ++i)
    displs[i] = displs[i - 1] + counts[i - 1];
  std::vector<double> all(displs.back() + counts.back());
  MPI_Allgatherv(local.data(), nloc, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, comm);
  std::vector<std::array<double, N>> rows(all.size() / N);
  for (std::size_t i = 0; i < rows.size(); ++i)
    std::copy_n(all.begin() + N * i, N, rows[i].begin());
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end(),
                         [](auto& a, auto& b) { return std::abs(a[0] - b[0]) < 1e-12; }),
             rows.end());
  return rows;
}
} // namespace

ObservableProbe::ObservableProbe(const Model& m, std::array<double, 3> p)
{
  _X = m.space()->tabulate_dof_coordinates(false);
  _skin = m.boundary_nodes("skin");
  const auto base = m.boundary_nodes("base");
  std::set_intersection(_skin.begin(), _skin.end(), base.begin(), base.end(), std::back_inserter(_rim));
  int symmetry_nodes = static_cast<int>(m.boundary_nodes("symmetry").size());
  MPI_Allreduce(MPI_IN_PLACE, &symmetry_nodes, 1, MPI_INT, MPI_SUM, m.mesh().mesh->comm());
  _copies = symmetry_nodes > 0 ? 2 : 1;

  // Nipple: the skin node nearest to the reference point, over all ranks.
  struct
  {
    double d;
    int rank;
  } local{std::numeric_limits<double>::max(), 0}, global;
  MPI_Comm comm = m.mesh().mesh->comm();
  MPI_Comm_rank(comm, &local.rank);
  for (auto n : _skin)
  {
    const double d = std::hypot(_X[3 * n] - p[0], _X[3 * n + 1] - p[1], _X[3 * n + 2] - p[2]);
    if (d < local.d)
    {
      local.d = d;
      _apex_node = n;
    }
  }
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm);
  _apex_rank = global.rank;
  if (global.d > 1e-6)
    throw InputError("the nipple point is not a node of the skin mesh");
}

Observables ObservableProbe::measure(Model& m) const
{
  MPI_Comm comm = m.mesh().mesh->comm();
  int rank;
  MPI_Comm_rank(comm, &rank);
  auto u = m.displacement()->x()->array();
  auto pos = [&](std::int32_t n, int i) { return _X[3 * n + i] + u[3 * n + i]; };

  Observables o;
  double ext[3] = {-std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                   -std::numeric_limits<double>::max()};
  for (auto n : _skin)
  {
    ext[0] = std::max(ext[0], pos(n, 1));
    ext[1] = std::min(ext[1], pos(n, 2));
    ext[2] = std::max(ext[2], pos(n, 2));
  }
  MPI_Allreduce(MPI_IN_PLACE, &ext[0], 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &ext[1], 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, &ext[2], 1, MPI_DOUBLE, MPI_MAX, comm);
  o.projection = ext[0];
  o.z_min = ext[1];
  o.z_max = ext[2];

  if (rank == _apex_rank)
    for (int i = 0; i < 3; ++i)
      o.nipple[i] = pos(_apex_node, i);
  MPI_Bcast(o.nipple.data(), 3, MPI_DOUBLE, _apex_rank, comm);

  // Base rim: gather (reference angle, deformed position) from all ranks,
  // order by the angle about the y axis, drop duplicates (ghosts).
  std::vector<double> local;
  for (auto n : _rim)
    local.insert(local.end(), {std::atan2(_X[3 * n + 2], _X[3 * n]), pos(n, 0), pos(n, 1), pos(n, 2)});
  const auto rim = gather_by_angle<4>(local, comm);
  double arc = 0;
  for (std::size_t i = 1; i < rim.size(); ++i)
    arc += std::hypot(rim[i][1] - rim[i - 1][1], rim[i][2] - rim[i - 1][2], rim[i][3] - rim[i - 1][3]);
  if (_copies == 1 && rim.size() > 2) // the full rim is closed
    arc += std::hypot(rim.front()[1] - rim.back()[1], rim.front()[2] - rim.back()[2], rim.front()[3] - rim.back()[3]);
  o.base_perimeter = _copies * arc;
  o.volume = _copies * m.volume();
  o.energy = _copies * m.energy();
  return o;
}

namespace
{
/// d of the rim polyline's length: rows (angle, x, y, z, du_x, du_y, du_z)
/// from every rank, in measure()'s order (by angle, duplicates dropped),
/// d |x_k - x_{k-1}| = (x_k - x_{k-1}) . (du_k - du_{k-1}) / |x_k - x_{k-1}|.
double rim_length_derivative(const std::vector<double>& local, bool closed, MPI_Comm comm)
{
  const auto rim = gather_by_angle<7>(local, comm);
  auto segment = [](const std::array<double, 7>& a, const std::array<double, 7>& b)
  {
    const double dx[3] = {b[1] - a[1], b[2] - a[2], b[3] - a[3]};
    const double len = std::hypot(dx[0], dx[1], dx[2]);
    return (dx[0] * (b[4] - a[4]) + dx[1] * (b[5] - a[5]) + dx[2] * (b[6] - a[6])) / len;
  };
  double arc = 0;
  for (std::size_t i = 1; i < rim.size(); ++i)
    arc += segment(rim[i - 1], rim[i]);
  if (closed && rim.size() > 2)
    arc += segment(rim.back(), rim.front());
  return arc;
}
} // namespace

Observables ObservableProbe::derivative(const Model& m, std::span<const double> du) const
{
  MPI_Comm comm = m.mesh().mesh->comm();
  int rank;
  MPI_Comm_rank(comm, &rank);
  auto u = m.displacement()->x()->array();
  auto pos = [&](std::int32_t n, int i) { return _X[3 * n + i] + u[3 * n + i]; };

  // The extreme nodes as measure() finds them (a tie between ranks goes to
  // the lower rank: MPI_MAXLOC/MINLOC); that rank gives du there.
  struct Loc
  {
    double v;
    int rank;
  };
  Loc ext[3] = {{-std::numeric_limits<double>::max(), rank},
                {std::numeric_limits<double>::max(), rank},
                {-std::numeric_limits<double>::max(), rank}};
  std::int32_t node[3] = {-1, -1, -1};
  for (auto n : _skin)
  {
    if (pos(n, 1) > ext[0].v)
      ext[0].v = pos(n, 1), node[0] = n;
    if (pos(n, 2) < ext[1].v)
      ext[1].v = pos(n, 2), node[1] = n;
    if (pos(n, 2) > ext[2].v)
      ext[2].v = pos(n, 2), node[2] = n;
  }
  Loc global[3];
  MPI_Allreduce(&ext[0], &global[0], 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm);
  MPI_Allreduce(&ext[1], &global[1], 1, MPI_DOUBLE_INT, MPI_MINLOC, comm);
  MPI_Allreduce(&ext[2], &global[2], 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm);
  const int component[3] = {1, 2, 2};
  double d[6] = {0, 0, 0, 0, 0, 0}; // projection, z_min, z_max, nipple
  for (int k = 0; k < 3; ++k)
    if (global[k].rank == rank && node[k] >= 0)
      d[k] = du[3 * node[k] + component[k]];
  if (rank == _apex_rank)
    for (int i = 0; i < 3; ++i)
      d[3 + i] = du[3 * _apex_node + i];
  MPI_Allreduce(MPI_IN_PLACE, d, 6, MPI_DOUBLE, MPI_SUM, comm);

  Observables o;
  o.projection = d[0];
  o.z_min = d[1];
  o.z_max = d[2];
  o.nipple = {d[3], d[4], d[5]};
  std::vector<double> rim;
  for (auto n : _rim)
    rim.insert(rim.end(), {std::atan2(_X[3 * n + 2], _X[3 * n]), pos(n, 0), pos(n, 1), pos(n, 2),
                           du[3 * n], du[3 * n + 1], du[3 * n + 2]});
  o.base_perimeter = _copies * rim_length_derivative(rim, _copies == 1, comm);
  o.volume = std::numeric_limits<double>::quiet_NaN(); // not measured: not differentiated
  o.energy = std::numeric_limits<double>::quiet_NaN();
  return o;
}
} // namespace breastsim
