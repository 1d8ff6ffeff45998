// SPDX-License-Identifier: LGPL-3.0-or-later
#include "mesh_quality.hpp"
#include <array>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/mesh/Topology.h>
#include <cmath>
#include <limits>

namespace breastsim
{
namespace
{
using V3 = std::array<double, 3>;
V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(const V3& a, const V3& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const V3& a) { return std::sqrt(dot(a, a)); }
} // namespace

MeshQuality mesh_quality(const dolfinx::mesh::Mesh& mesh)
{
  const auto& geom = mesh.geometry();
  const auto& dofmap = geom.dofmap();
  auto x = geom.x();
  const std::int32_t ncells = mesh.topology().index_map(3)->size_local();
  double dmin = 180, dmax = 0, rmin = 1e300, rsum = 0, hmin = 1e300, hmax = 0;
  static const int faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  static const int edges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    auto nodes = dofmap.links(c);
    std::array<V3, 4> p;
    for (int i = 0; i < 4; ++i)
      p[i] = {x[3 * nodes[i]], x[3 * nodes[i] + 1], x[3 * nodes[i] + 2]};
    // Outward face normals; the dihedral angle at the edge shared by faces
    // i and j is pi - angle(n_i, n_j).
    std::array<V3, 4> n;
    double area = 0;
    for (int f = 0; f < 4; ++f)
    {
      const auto& a = p[faces[f][0]];
      V3 nf = cross(sub(p[faces[f][1]], a), sub(p[faces[f][2]], a));
      if (dot(nf, sub(a, p[f])) < 0)
        nf = {-nf[0], -nf[1], -nf[2]};
      area += 0.5 * norm(nf);
      n[f] = nf;
    }
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
      {
        const double cosang = -dot(n[i], n[j]) / (norm(n[i]) * norm(n[j]));
        const double ang = std::acos(std::clamp(cosang, -1.0, 1.0)) * 180 / M_PI;
        dmin = std::min(dmin, ang);
        dmax = std::max(dmax, ang);
      }
    for (auto& e : edges)
    {
      const double h = norm(sub(p[e[0]], p[e[1]]));
      hmin = std::min(hmin, h);
      hmax = std::max(hmax, h);
    }
    // r_in = 3 V / A; circumradius from the standard formula.
    const V3 a = sub(p[1], p[0]), b = sub(p[2], p[0]), cc = sub(p[3], p[0]);
    const double vol6 = std::abs(dot(a, cross(b, cc)));
    const double r_in = (vol6 / 6) * 3 / area;
    V3 num;
    const V3 t1 = cross(b, cc), t2 = cross(cc, a), t3 = cross(a, b);
    for (int i = 0; i < 3; ++i)
      num[i] = dot(a, a) * t1[i] + dot(b, b) * t2[i] + dot(cc, cc) * t3[i];
    const double r_circ = norm(num) / (2 * vol6);
    const double rr = 3 * r_in / r_circ;
    rmin = std::min(rmin, rr);
    rsum += rr;
  }
  MeshQuality q;
  MPI_Comm comm = mesh.comm();
  MPI_Allreduce(&dmin, &q.min_dihedral_deg, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(&dmax, &q.max_dihedral_deg, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(&rmin, &q.min_radius_ratio, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(&hmin, &q.h_min, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(&hmax, &q.h_max, 1, MPI_DOUBLE, MPI_MAX, comm);
  double rs = 0;
  MPI_Allreduce(&rsum, &rs, 1, MPI_DOUBLE, MPI_SUM, comm);
  q.num_cells = mesh.topology().index_map(3)->size_global();
  q.num_vertices = mesh.topology().index_map(0)->size_global();
  q.mean_radius_ratio = rs / q.num_cells;
  return q;
}

nlohmann::json to_json(const MeshQuality& q)
{
  return {{"cells", q.num_cells},
          {"vertices", q.num_vertices},
          {"min_dihedral_deg", q.min_dihedral_deg},
          {"max_dihedral_deg", q.max_dihedral_deg},
          {"min_radius_ratio", q.min_radius_ratio},
          {"mean_radius_ratio", q.mean_radius_ratio},
          {"h_min_m", q.h_min},
          {"h_max_m", q.h_max}};
}
} // namespace breastsim
