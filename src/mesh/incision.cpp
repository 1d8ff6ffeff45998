// SPDX-License-Identifier: LGPL-3.0-or-later
#include "incision.hpp"
#include "errors.hpp"
#include <cmath>
#include <fmt/format.h>
#include <gmsh.h>

namespace breastsim::meshes
{
namespace
{
double dot(const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
} // namespace

int half_space_box(const Point& n, double c, double L)
{
  namespace occ = gmsh::model::occ;
  // Box {x' in [-L, 0]} in a frame whose x' axis is n, centred on the plane.
  const int box = occ::addBox(-L, -L, -L, L, 2 * L, 2 * L);
  // Rotate e_x onto n: axis e_x x n, angle acos(n_x).
  const Point axis = {0.0, -n[2], n[1]};
  const double s = std::sqrt(dot(axis, axis));
  if (s > 1e-14)
    occ::rotate({{3, box}}, 0, 0, 0, axis[0] / s, axis[1] / s, axis[2] / s,
                std::atan2(s, n[0]));
  occ::translate({{3, box}}, c * n[0], c * n[1], c * n[2]);
  return box;
}

double add_volume_group(const std::vector<std::pair<int, int>>& vols, std::vector<int>& faces)
{
  std::vector<int> ids;
  double volume = 0;
  for (auto [d, t] : vols)
  {
    ids.push_back(t);
    double m;
    gmsh::model::occ::getMass(d, t, m);
    volume += m;
  }
  gmsh::model::addPhysicalGroup(3, ids, 1);
  gmsh::vectorpair boundary;
  gmsh::model::getBoundary(vols, boundary, false, false, false);
  faces.clear();
  for (auto [d, t] : boundary)
    faces.push_back(std::abs(t));
  return volume;
}

bool IncisionGeometry::resected(const Point& p) const
{
  return dot(n1, p) < c1 || dot(n2, p) < c2;
}

IncisionGeometry incision_geometry(const HalfCapSpec& cap, const IncisionSpec& in)
{
  const double R = cap.R, H = cap.H, Rs = sphere_radius(R, H), yc = H - Rs;
  const double a = in.a_deg * M_PI / 180, ta = std::tan(a);
  if (!(in.a_deg > 0 && in.a_deg < 90))
    throw InputError(fmt::format("key 'incision.a_deg' = {} is out of range: allowed (0, 90) deg", in.a_deg));
  // A = (0, y_A, s) on the sphere (y - yc)^2 + z^2 = Rs^2 with y_A > 0.
  if (!(in.s >= 0 && in.s < R))
    throw InputError(fmt::format("key 'incision.s' = {} m: the new nipple A = (0, y, s) must lie on the "
                                 "skin, allowed [0, R) = [0, {:.6g}) m", in.s, R));
  IncisionGeometry g;
  g.A = {0.0, yc + std::sqrt(Rs * Rs - in.s * in.s), in.s};
  // D on the skin with y = h on P1: x = (s - z) tan a, x^2 + (h - yc)^2 + z^2 = Rs^2, z < s.
  const double rho2 = Rs * Rs - (in.h - yc) * (in.h - yc); // x^2 + z^2 at height h
  if (!(in.h > 0 && in.h < H) || rho2 <= 0)
    throw InputError(fmt::format("key 'incision.h' = {} m: D must lie on the skin, allowed (0, H) = (0, {:.6g}) m",
                                 in.h, H));
  // (1 + t^2) z^2 - 2 s t^2 z + s^2 t^2 - rho2 = 0, lower root.
  const double qa = 1 + ta * ta, qb = -2 * in.s * ta * ta, qc = in.s * in.s * ta * ta - rho2;
  const double disc = qb * qb - 4 * qa * qc;
  if (disc <= 0)
    throw InputError(fmt::format("key 'incision.a_deg' = {}: plane P1 does not reach the skin at height "
                                 "incision.h = {} m (D does not exist)", in.a_deg, in.h));
  const double zD = (-qb - std::sqrt(disc)) / (2 * qa);
  g.D = {(in.s - zD) * ta, in.h, zD};
  if (!(in.d >= 0 && in.d < R))
    throw InputError(fmt::format("key 'incision.d' = {} m is out of range: C = (0, 0, -d) must lie on the base, "
                                 "allowed [0, R) = [0, {:.6g}) m", in.d, R));
  g.C = {0.0, 0.0, -in.d};
  g.B = {(in.s + in.d) * ta, 0.0, -in.d};
  if (g.B[0] * g.B[0] + in.d * in.d >= R * R)
    throw InputError(fmt::format("key 'incision.a_deg' = {}: B = ({:.4g}, 0, {:.4g}) falls outside the base "
                                 "(radius {:.4g} m); reduce a, s or d", in.a_deg, g.B[0], g.B[2], R));
  // P1: n1 = (cos a, 0, sin a), through (0, *, s); remaining side n1 . p > c1.
  g.n1 = {std::cos(a), 0.0, std::sin(a)};
  g.c1 = std::sin(a) * in.s;
  // P2: through C and D, containing e_x: normal ~ (0, -(zD + d), h), oriented towards A.
  Point n2 = {0.0, -(zD + in.d), in.h};
  const double nn = std::sqrt(dot(n2, n2));
  for (auto& v : n2)
    v /= nn;
  double c2 = dot(n2, g.C);
  if (dot(n2, g.A) < c2)
  {
    for (auto& v : n2)
      v = -v;
    c2 = -c2;
  }
  g.n2 = n2;
  g.c2 = c2;
  if (!(dot(n2, g.A) > c2 + 1e-9))
    throw InputError("key 'incision.h': the new nipple A lies on P2; the incision is degenerate");
  return g;
}

namespace
{
/// The neutral half cap as an OCC volume (the sphere cut to x >= 0, y >= 0)
/// and the two half-space boxes {n1 . p < c1}, {n2 . p < c2} of the cuts.
struct CutBodies
{
  gmsh::vectorpair body;
  int k1, k2;
};

CutBodies cap_and_cuts(const HalfCapSpec& cap, const IncisionGeometry& g)
{
  namespace occ = gmsh::model::occ;
  const double Rs = sphere_radius(cap.R, cap.H), yc = cap.H - Rs, L = 8 * Rs;
  const int sphere = occ::addSphere(0, yc, 0, Rs);
  const int quarter = occ::addBox(0, 0, -L, L, L, 2 * L);
  CutBodies b;
  std::vector<gmsh::vectorpair> map;
  occ::intersect({{3, sphere}}, {{3, quarter}}, b.body, map);
  b.k1 = half_space_box(g.n1, g.c1, L);
  b.k2 = half_space_box(g.n2, g.c2, L);
  return b;
}

/// Physical groups of the volumes `vols` (tag 1) and of their boundary faces:
/// base (y = 0), skin (curved), symmetry (x = 0), on P1, on P2, with the tag
/// values `tags` in that order. Returns the CAD volume and whether faces on
/// P1 and P2 exist.
double tag_faces(const gmsh::vectorpair& vols, const IncisionGeometry& g, double Rs,
                 const std::array<int, 5>& tags, bool& on_p1, bool& on_p2)
{
  namespace occ = gmsh::model::occ;
  std::vector<int> base, skin, sym, abd, bcd;
  std::vector<int> faces;
  const double volume = add_volume_group(vols, faces);
  const double tol = 1e-6 * Rs;
  for (int t : faces)
  {
    double x, y, z;
    occ::getCenterOfMass(2, t, x, y, z);
    const Point p = {x, y, z};
    std::string type;
    gmsh::model::getType(2, t, type);
    if (type != "Plane")
      skin.push_back(t);
    else if (std::abs(y) < tol)
      base.push_back(t);
    else if (std::abs(x) < tol)
      sym.push_back(t);
    else if (std::abs(dot(g.n1, p) - g.c1) < tol)
      abd.push_back(t);
    else if (std::abs(dot(g.n2, p) - g.c2) < tol)
      bcd.push_back(t);
    else
      throw std::runtime_error("incision: unclassified planar face");
  }
  const std::vector<int>* groups[5] = {&base, &skin, &sym, &abd, &bcd};
  for (int i = 0; i < 5; ++i)
    if (!groups[i]->empty())
      gmsh::model::addPhysicalGroup(2, *groups[i], tags[i]);
  on_p1 = !abd.empty();
  on_p2 = !bcd.empty();
  return volume;
}

} // namespace

void set_incision_mesh_options(double mesh_size)
{
  gmsh::option::setNumber("Mesh.MeshSizeMin", 0.5 * mesh_size);
  gmsh::option::setNumber("Mesh.MeshSizeMax", mesh_size);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.Algorithm3D", 1);
  gmsh::option::setNumber("Mesh.Optimize", 1);
  gmsh::option::setNumber("General.NumThreads", 1);
}

TaggedMesh mesh_incised_cap(const HalfCapSpec& cap, const IncisionSpec& inc,
                            const std::array<int, 5>& tags, double* cad_volume)
{
  namespace occ = gmsh::model::occ;
  const IncisionGeometry g = incision_geometry(cap, inc);
  GmshSession session;
  auto cut = cap_and_cuts(cap, g);
  gmsh::vectorpair kept;
  std::vector<gmsh::vectorpair> map;
  occ::cut(cut.body, {{3, cut.k1}, {3, cut.k2}}, kept, map);
  occ::synchronize();
  if (kept.empty())
    throw InputError("the incision removes the whole breast: check incision.a_deg, incision.s, incision.h, incision.d");
  bool p1 = false, p2 = false;
  const double volume = tag_faces(kept, g, sphere_radius(cap.R, cap.H), tags, p1, p2);
  if (!p1 || !p2)
    throw InputError("the incision planes miss the breast (no cut face on P1 or P2): check incision.a_deg, "
                     "incision.h, incision.d");
  set_incision_mesh_options(cap.mesh_size);
  if (cad_volume)
    *cad_volume = volume;
  return extract_tagged_mesh(cap.order, cap.refinements);
}

TaggedMesh mesh_resected_part(const HalfCapSpec& cap, const IncisionSpec& inc,
                              const std::array<int, 5>& tags, double* cad_volume)
{
  namespace occ = gmsh::model::occ;
  const IncisionGeometry g = incision_geometry(cap, inc);
  GmshSession session;
  auto cut = cap_and_cuts(cap, g);
  // The resected part: the cap inside the union of the two half-spaces.
  gmsh::vectorpair cuts, resected;
  std::vector<gmsh::vectorpair> map;
  occ::fuse({{3, cut.k1}}, {{3, cut.k2}}, cuts, map);
  occ::intersect(cut.body, cuts, resected, map);
  occ::synchronize();
  if (resected.empty())
    throw InputError("the incision removes nothing: check incision.a_deg, incision.s, incision.h, incision.d");
  bool p1 = false, p2 = false;
  const double volume = tag_faces(resected, g, sphere_radius(cap.R, cap.H), tags, p1, p2);
  set_incision_mesh_options(cap.mesh_size);
  if (cad_volume)
    *cad_volume = volume;
  return extract_tagged_mesh(cap.order, cap.refinements);
}
} // namespace breastsim::meshes
