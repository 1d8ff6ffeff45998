// SPDX-License-Identifier: LGPL-3.0-or-later
#include "half_cap.hpp"
#include <algorithm>
#include <cmath>
#include <gmsh.h>

namespace breastsim::meshes
{
double sphere_radius(double R, double H) { return (R * R + H * H) / (2 * H); }

namespace
{
/// Which of the planes y = 0 (base), x = 0 (symmetry) and z = 0 (the two
/// halves' interface) a gmsh entity lies in, by its bounding box (OCC pads
/// boxes by the geometric tolerance, ~1e-7 m; `tol` is larger).
struct Planes
{
  bool base, symmetry, interface;
};
Planes planes_of(int dim, int tag, double tol)
{
  double x0, y0, z0, x1, y1, z1;
  gmsh::model::getBoundingBox(dim, tag, x0, y0, z0, x1, y1, z1);
  return {std::abs(y1) < tol, std::abs(x1) < tol, std::abs(z0) < tol && std::abs(z1) < tol};
}

/// Element size h(d) = rim_size_ratio mesh_size at the base rim (the arc where
/// skin meets base), growing linearly with the distance d to mesh_size at
/// d = 2 mesh_size (gmsh Distance + Threshold fields).
void grade_toward_rim(const HalfCapSpec& s, double tol)
{
  gmsh::vectorpair curves;
  gmsh::model::getEntities(curves, 1);
  std::vector<double> rim;
  for (auto [d, t] : curves)
    if (const Planes p = planes_of(d, t, tol); p.base && !p.symmetry && !p.interface)
      rim.push_back(t);
  namespace field = gmsh::model::mesh::field;
  const int distance = field::add("Distance");
  field::setNumbers(distance, "CurvesList", rim);
  field::setNumber(distance, "NumPointsPerCurve", 200);
  const int threshold = field::add("Threshold");
  field::setNumber(threshold, "InField", distance);
  field::setNumber(threshold, "SizeMin", s.rim_size_ratio * s.mesh_size);
  field::setNumber(threshold, "SizeMax", s.mesh_size);
  field::setNumber(threshold, "DistMin", 0.0);
  field::setNumber(threshold, "DistMax", 2 * s.mesh_size);
  field::setAsBackgroundMesh(threshold);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
}
} // namespace

void build_half_cap_geometry(const HalfCapSpec& s, int tag_base, int tag_skin,
                             int tag_symmetry)
{
  namespace occ = gmsh::model::occ;
  const double Rs = sphere_radius(s.R, s.H);
  const double yc = s.H - Rs; // sphere centre (0, yc, 0)
  const double L = 4 * Rs;    // box extent beyond the sphere

  // Half cap = sphere intersected with {x >= 0, y >= 0}, in two halves
  // z >= 0 and z <= 0 glued by fragment (the apex becomes a vertex).
  std::vector<std::pair<int, int>> halves;
  for (double z0 : {0.0, -L})
  {
    const int sphere = occ::addSphere(0, yc, 0, Rs);
    const int box = occ::addBox(0, 0, z0, L, L, L);
    gmsh::vectorpair out;
    std::vector<gmsh::vectorpair> map;
    occ::intersect({{3, sphere}}, {{3, box}}, out, map);
    halves.insert(halves.end(), out.begin(), out.end());
  }
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> map;
  occ::fragment({halves[0]}, {halves[1]}, out, map);
  occ::synchronize();

  std::vector<int> vols, base, skin, sym;
  gmsh::vectorpair ents;
  gmsh::model::getEntities(ents, 3);
  for (auto [d, t] : ents)
    vols.push_back(t);
  gmsh::model::getEntities(ents, 2);
  // Classify by bounding box: planar faces y = 0, x = 0, z = 0 and the
  // sphere. The tolerance scales with the geometry, not the mesh: with 1e-4 h a
  // 1 mm mesh took the padded z = 0 interface for skin.
  const double tol = 1e-3 * std::min(s.R, s.H);
  for (auto [d, t] : ents)
  {
    const Planes p = planes_of(d, t, tol);
    if (p.base)
      base.push_back(t);
    else if (p.symmetry)
      sym.push_back(t);
    else if (!p.interface) // z = 0: the halves' internal interface
      skin.push_back(t);
  }
  gmsh::model::addPhysicalGroup(3, vols, 1);
  gmsh::model::addPhysicalGroup(2, base, tag_base);
  gmsh::model::addPhysicalGroup(2, skin, tag_skin);
  gmsh::model::addPhysicalGroup(2, sym, tag_symmetry);

  if (s.rim_size_ratio < 1)
    grade_toward_rim(s, tol);
  gmsh::option::setNumber("Mesh.MeshSizeMin", 0.5 * s.rim_size_ratio * s.mesh_size);
  gmsh::option::setNumber("Mesh.MeshSizeMax", s.mesh_size);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.Algorithm3D", 1); // Delaunay: deterministic
  gmsh::option::setNumber("Mesh.Optimize", 1);
  gmsh::option::setNumber("General.NumThreads", 1);
}

TaggedMesh mesh_half_cap(const HalfCapSpec& spec, int tag_base, int tag_skin,
                         int tag_symmetry)
{
  GmshSession session;
  build_half_cap_geometry(spec, tag_base, tag_skin, tag_symmetry);
  return extract_tagged_mesh(spec.order, spec.refinements);
}
} // namespace breastsim::meshes
