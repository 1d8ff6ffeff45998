// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_mesh.hpp"
#include "errors.hpp"
#include <cmath>
#include <gmsh.h>
#include <stdexcept>

namespace breastsim::scan
{
namespace
{
/// Mean radius of the fitted skin over the disk.
double mean_radius(const RadialSurface& f)
{
  double sum = 0;
  int count = 0;
  for (int a = -20; a <= 20; ++a)
    for (int b = -20; b <= 20; ++b)
      if (std::hypot(a, b) <= 20)
      {
        sum += f.radius(a / 20.0, b / 20.0);
        ++count;
      }
  return sum / count;
}

/// The (half) ball of radius rm in y >= 0 with the point rm d as a vertex;
/// physical groups: volume 1, base, skin, symmetry.
void build_ball(double rm, const Vec3& d, const ScanMeshOptions& o, int tag_base, int tag_skin, int tag_symmetry)
{
  namespace occ = gmsh::model::occ;
  const double L = 3 * rm;
  const int sphere = occ::addSphere(0, 0, 0, rm);
  const int box = occ::addBox(o.half ? 0 : -L, 0, -L, o.half ? L : 2 * L, L, 2 * L);
  gmsh::vectorpair body, pieces;
  std::vector<gmsh::vectorpair> map;
  occ::intersect({{3, sphere}}, {{3, box}}, body, map);
  const int apex = occ::addPoint(rm * d[0], rm * d[1], rm * d[2]);
  occ::fragment(body, {{0, apex}}, pieces, map);
  occ::synchronize();
  std::vector<int> vols, base, skin, sym;
  gmsh::vectorpair ents;
  gmsh::model::getEntities(ents, 3);
  for (auto [dim, t] : ents)
    vols.push_back(t);
  gmsh::model::getEntities(ents, 2);
  const double tol = 1e-3 * rm;
  for (auto [dim, t] : ents)
  {
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(dim, t, x0, y0, z0, x1, y1, z1);
    (std::abs(y1) < tol ? base : (o.half && std::abs(x1) < tol) ? sym : skin).push_back(t);
  }
  gmsh::model::addPhysicalGroup(3, vols, 1);
  gmsh::model::addPhysicalGroup(2, base, tag_base);
  gmsh::model::addPhysicalGroup(2, skin, tag_skin);
  if (o.half)
    gmsh::model::addPhysicalGroup(2, sym, tag_symmetry);
  gmsh::option::setNumber("Mesh.MeshSizeMin", 0.5 * o.mesh_size);
  gmsh::option::setNumber("Mesh.MeshSizeMax", o.mesh_size);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.Algorithm3D", 1); // Delaunay: deterministic
  gmsh::option::setNumber("Mesh.Optimize", 1);
  gmsh::option::setNumber("General.NumThreads", 1);
}

/// Signed volume of the corners a, b, c, d: (b - a) . ((c - a) x (d - a)) / 6.
double corner_volume(const meshes::TaggedMesh& m, std::size_t c)
{
  auto node = [&](int k)
  {
    const std::int64_t n = m.cells[c * m.nodes_per_cell() + k];
    return Vec3{m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]};
  };
  const Vec3 a = node(0);
  return dot(node(1) - a, cross(node(2) - a, node(3) - a)) / 6;
}
} // namespace

ScanMesh mesh_scan(const RadialSurface& skin, const Vec3& nipple, const ScanMeshOptions& o, int tag_base,
                   int tag_skin, int tag_symmetry)
{
  const double rm = mean_radius(skin);
  const Vec3 d = (1 / norm(nipple)) * nipple;
  ScanMesh out;
  {
    meshes::GmshSession session;
    build_ball(rm, d, o, tag_base, tag_skin, tag_symmetry);
    out.mesh = meshes::extract_tagged_mesh(o.order, 0);
  }
  std::vector<double> before(out.mesh.num_cells());
  for (std::size_t c = 0; c < before.size(); ++c)
    before[c] = corner_volume(out.mesh, c);
  double nearest = 1e300;
  for (std::size_t n = 0; n < out.mesh.num_nodes(); ++n)
  {
    const Vec3 X{out.mesh.x[3 * n], out.mesh.x[3 * n + 1], out.mesh.x[3 * n + 2]};
    const double s = norm(X);
    if (s == 0)
      continue;
    // x = (|X| / r_m) r(X / |X|) X / |X|; the plane y = 0 stays (d_y = 0 there)
    const Vec3 x = (skin.radius((1 / s) * X) / rm) * X;
    std::copy(x.begin(), x.end(), out.mesh.x.begin() + 3 * n);
    if (const double gap = norm(X - rm * d); gap < nearest)
    {
      nearest = gap;
      out.nipple = x;
    }
  }
  if (nearest > 1e-6 * rm)
    throw std::runtime_error(fmt::format("mesh_scan: no node at the nipple direction (nearest {:.3g} m)", nearest));
  for (std::size_t c = 0; c < before.size(); ++c)
  {
    const double v = corner_volume(out.mesh, c);
    if (!(v * before[c] > 0))
      throw InputError(fmt::format("the fitted skin folds: tetrahedron {} is inverted when moved onto it (near "
                                   "({:.1f}, {:.1f}, {:.1f}) mm in the breast frame)",
                                   c, 1e3 * out.mesh.x[3 * out.mesh.cells[c * out.mesh.nodes_per_cell()]],
                                   1e3 * out.mesh.x[3 * out.mesh.cells[c * out.mesh.nodes_per_cell()] + 1],
                                   1e3 * out.mesh.x[3 * out.mesh.cells[c * out.mesh.nodes_per_cell()] + 2]));
    out.volume += std::abs(v);
  }
  out.nipple[0] = 0; // the sagittal plane through the nipple is x = 0
  return out;
}
} // namespace breastsim::scan
