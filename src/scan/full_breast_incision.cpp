// SPDX-License-Identifier: LGPL-3.0-or-later
#include "full_breast_incision.hpp"
#include "errors.hpp"
#include "incision.hpp"
#include "skin_solid.hpp"
#include <cmath>
#include <fmt/format.h>
#include <gmsh.h>

namespace breastsim::scan
{
namespace
{
/// |P| - r(P / |P|): negative inside the skin, positive outside.
double outside_skin(const RadialSurface& skin, const Vec3& P) { return norm(P) - skin.radius((1 / norm(P)) * P); }

/// The root of f on [a, b] (f(a) <= 0 < f(b)) by bisection.
template <class F>
double bisect(F f, double a, double b)
{
  for (int i = 0; i < 80; ++i)
  {
    const double m = 0.5 * (a + b);
    (f(m) <= 0 ? a : b) = m;
  }
  return 0.5 * (a + b);
}

/// The base rim's radius in the direction (cos phi, 0, sin phi).
double rim_radius(const RadialSurface& skin, double phi) { return skin.radius({std::cos(phi), 0.0, std::sin(phi)}); }

/// A = (0, y_A, s): the skin point of the plane x = 0 at height z = s (s >= 0).
Vec3 new_nipple(const RadialSurface& skin, double s)
{
  const double top = rim_radius(skin, M_PI / 2);
  if (!(s >= 0 && s < top))
    throw InputError(fmt::format("key 'incision.s' = {} m: the new nipple A = (0, y, s) must lie on the skin of "
                                 "this breast, allowed [0, {:.6g}) m (the upper rim of its base)", s, top));
  // the direction (0, cos t, sin t) at which the skin reaches z = s, t in [0, pi/2)
  auto height = [&](double t) { return skin.radius(Vec3{0.0, std::cos(t), std::sin(t)}) * std::sin(t) - s; };
  const double t = s == 0 ? 0.0 : bisect(height, 0.0, 0.5 * M_PI);
  return skin.radius(Vec3{0.0, std::cos(t), std::sin(t)}) * Vec3{0.0, std::cos(t), std::sin(t)};
}

/// D (side +1) or D' (side -1): the skin point ((s - z) tan a side, h, z), z < s.
Vec3 skin_point_on_p1(const RadialSurface& skin, const IncisionSpec& in, double y_A, int side)
{
  const double ta = std::tan(in.a_deg * M_PI / 180);
  auto point = [&](double z) { return Vec3{side * (in.s - z) * ta, in.h, z}; };
  if (!(in.h > 0 && in.h < y_A))
    throw InputError(fmt::format("key 'incision.h' = {} m: D (the skin point on P1 at y = h below A) must lie on "
                                 "the skin below the new nipple A, allowed (0, {:.6g}) m (the height y_A of A)",
                                 in.h, y_A));
  if (outside_skin(skin, point(in.s)) > 0)
    throw InputError(fmt::format("key 'incision.h' = {} m: the point (0, h, s) of P1 below A lies outside this "
                                 "breast, so D does not exist; allowed h below the skin at z = s", in.h));
  const double reach = 4 * rim_radius(skin, -M_PI / 2) + in.s;
  double z = in.s;
  while (outside_skin(skin, point(z)) <= 0)
  {
    z -= 1e-3;
    if (z < in.s - reach)
      throw InputError(fmt::format("key 'incision.a_deg' = {}: plane P1{} does not reach the skin at height "
                                   "incision.h = {} m (D does not exist on this breast)",
                                   in.a_deg, side > 0 ? "" : "'", in.h));
  }
  // w = -z grows downwards: inside at w = -(z + 1 mm), outside at w = -z
  const double w = bisect([&](double ww) { return outside_skin(skin, point(-ww)); }, -(z + 1e-3), -z);
  return point(-w);
}

/// B (side +1), B' (side -1) = ((s + d) tan a side, 0, -d), inside the base.
Vec3 base_corner(const RadialSurface& skin, const IncisionSpec& in, int side)
{
  const double ta = std::tan(in.a_deg * M_PI / 180);
  const Vec3 B = {side * (in.s + in.d) * ta, 0.0, -in.d};
  const double rim = skin.radius((1 / norm(B)) * B);
  if (norm(B) >= rim)
    throw InputError(fmt::format("key 'incision.a_deg' = {}: B{} = ({:.4g}, 0, {:.4g}) m falls outside the base of "
                                 "this breast (its rim is {:.4g} m from the centre there); reduce a, s or d",
                                 in.a_deg, side > 0 ? "" : "'", B[0], B[2], rim));
  return B;
}
} // namespace

bool FullIncisionGeometry::resected(const Vec3& p) const
{
  return (dot(n1, p) < c1 && dot(n1_mirror, p) < c1) || dot(n2, p) < c2;
}

FullIncisionGeometry full_incision_geometry(const RadialSurface& skin, const IncisionSpec& in)
{
  if (!(in.a_deg > 0 && in.a_deg < 90))
    throw InputError(fmt::format("key 'incision.a_deg' = {} is out of range: allowed (0, 90) deg", in.a_deg));
  FullIncisionGeometry g;
  g.A = new_nipple(skin, in.s);
  g.D = skin_point_on_p1(skin, in, g.A[1], +1);
  g.D_mirror = skin_point_on_p1(skin, in, g.A[1], -1);
  const double bottom = rim_radius(skin, -M_PI / 2);
  if (!(in.d >= 0 && in.d < bottom))
    throw InputError(fmt::format("key 'incision.d' = {} m is out of range: C = (0, 0, -d) must lie on the base of "
                                 "this breast, allowed [0, {:.6g}) m (its lower rim)", in.d, bottom));
  g.C = {0.0, 0.0, -in.d};
  g.B = base_corner(skin, in, +1);
  g.B_mirror = base_corner(skin, in, -1);
  const double a = in.a_deg * M_PI / 180;
  g.n1 = {std::cos(a), 0.0, std::sin(a)};
  g.n1_mirror = {-std::cos(a), 0.0, std::sin(a)};
  g.c1 = std::sin(a) * in.s;
  // P2 through C and (*, h, z_P2), containing e_x: normal ~ (0, -(z_P2 + d), h), towards A.
  const double zP2 = 0.5 * (g.D[2] + g.D_mirror[2]);
  Vec3 n2 = {0.0, -(zP2 + in.d), in.h};
  n2 = (1 / norm(n2)) * n2;
  if (dot(n2, g.A) < dot(n2, g.C))
    n2 = -1.0 * n2;
  g.n2 = n2;
  g.c2 = dot(n2, g.C);
  if (!(dot(n2, g.A) > g.c2 + 1e-9))
    throw InputError(fmt::format("key 'incision.h' = {} m: the new nipple A lies on P2; the incision is degenerate",
                                 in.h));
  return g;
}

namespace
{
/// The total area of the faces `faces`.
double area(const std::vector<int>& faces)
{
  double total = 0;
  for (int f : faces)
  {
    double a;
    gmsh::model::occ::getMass(2, f, a);
    total += a;
  }
  return total;
}

/// Physical groups of the volumes `vols` (tag 1) and of their boundary faces:
/// base (y = 0), the keel faces on P1 and P1' (the smaller one suture_a, the
/// other suture_b; `mirror_is_a`: the one on P1'), suture_bcd (P2), skin (the
/// rest). Returns the CAD volume; `cut_faces` counts the faces on P1, P1', P2.
double tag_full_faces(const gmsh::vectorpair& vols, const FullIncisionGeometry& g, const FullIncisionTags& tags,
                      std::array<int, 3>& cut_faces, bool& mirror_is_a)
{
  namespace occ = gmsh::model::occ;
  std::vector<int> base, skin, on_p1, on_p1m, on_p2;
  std::vector<int> faces;
  const double volume = meshes::add_volume_group(vols, faces);
  const double tol = 1e-6 * norm(g.A);
  for (int t : faces)
  {
    Vec3 p;
    occ::getCenterOfMass(2, t, p[0], p[1], p[2]);
    std::string type;
    gmsh::model::getType(2, t, type);
    if (type != "Plane")
      skin.push_back(t);
    else if (std::abs(p[1]) < tol)
      base.push_back(t);
    else if (std::abs(dot(g.n1, p) - g.c1) < tol)
      on_p1.push_back(t);
    else if (std::abs(dot(g.n1_mirror, p) - g.c1) < tol)
      on_p1m.push_back(t);
    else if (std::abs(dot(g.n2, p) - g.c2) < tol)
      on_p2.push_back(t);
    else
      skin.push_back(t);
  }
  // Face A (whose nodes are sewn to their mirror images in face B) is the
  // smaller keel face: on an asymmetric breast its mirror image then lies
  // (nearly) inside the other.
  mirror_is_a = area(on_p1m) < area(on_p1);
  const std::pair<const std::vector<int>*, int> groups[] = {
      {&base, tags.base}, {&skin, tags.skin}, {&on_p1, mirror_is_a ? tags.suture_b : tags.suture_a},
      {&on_p1m, mirror_is_a ? tags.suture_a : tags.suture_b}, {&on_p2, tags.suture_bcd}};
  for (const auto& [list, tag] : groups)
    if (!list->empty())
      gmsh::model::addPhysicalGroup(2, *list, tag);
  cut_faces = {static_cast<int>(on_p1.size()), static_cast<int>(on_p1m.size()), static_cast<int>(on_p2.size())};
  return volume;
}

/// The solid under the skin and the two regions cut away: the keel (P1 and
/// P1' half-spaces intersected) and the lower pole (beyond P2).
struct FullCutBodies
{
  int solid;
  gmsh::vectorpair keel;
  int lower;
};

FullCutBodies solid_and_cuts(const RadialSurface& skin, const FullIncisionGeometry& g)
{
  namespace occ = gmsh::model::occ;
  FullCutBodies b;
  b.solid = add_skin_solid(skin);
  const double L = 20 * norm(g.A) + 1.0;
  const int k1 = meshes::half_space_box(g.n1, g.c1, L), k1m = meshes::half_space_box(g.n1_mirror, g.c1, L);
  std::vector<gmsh::vectorpair> map;
  occ::intersect({{3, k1}}, {{3, k1m}}, b.keel, map);
  b.lower = meshes::half_space_box(g.n2, g.c2, L);
  return b;
}
} // namespace

FullIncisionMeshes mesh_full_incision(const RadialSurface& skin, const FullIncisionGeometry& g,
                                      const FullIncisionTags& tags, double mesh_size, int order, int refinements)
{
  namespace occ = gmsh::model::occ;
  FullIncisionMeshes out;
  std::array<int, 3> cut_faces{};
  {
    meshes::GmshSession session;
    FullCutBodies b = solid_and_cuts(skin, g);
    occ::getMass(3, b.solid, out.volume_solid);
    gmsh::vectorpair tools = b.keel, kept;
    tools.push_back({3, b.lower});
    std::vector<gmsh::vectorpair> map;
    occ::cut({{3, b.solid}}, tools, kept, map);
    occ::synchronize();
    if (kept.empty())
      throw InputError("the incision removes the whole breast: check incision.a_deg, incision.s, incision.h, "
                       "incision.d");
    out.volume_kept = tag_full_faces(kept, g, tags, cut_faces, out.face_a_on_mirror);
    if (cut_faces[0] == 0 || cut_faces[1] == 0 || cut_faces[2] == 0)
      throw InputError(fmt::format("the incision planes miss the breast (cut faces on P1, P1', P2: {}, {}, {}): "
                                   "check incision.a_deg, incision.h, incision.d",
                                   cut_faces[0], cut_faces[1], cut_faces[2]));
    meshes::set_incision_mesh_options(mesh_size);
    out.kept = meshes::extract_tagged_mesh(order, refinements);
  }
  meshes::GmshSession session;
  FullCutBodies b = solid_and_cuts(skin, g);
  gmsh::vectorpair cuts, resected;
  std::vector<gmsh::vectorpair> map;
  occ::fuse(b.keel, {{3, b.lower}}, cuts, map);
  occ::intersect({{3, b.solid}}, cuts, resected, map);
  occ::synchronize();
  if (resected.empty())
    throw InputError("the incision removes nothing: check incision.a_deg, incision.s, incision.h, incision.d");
  bool resected_mirror_is_a = false;
  out.volume_resected = tag_full_faces(resected, g, tags, cut_faces, resected_mirror_is_a);
  meshes::set_incision_mesh_options(mesh_size);
  out.resected = meshes::extract_tagged_mesh(order, refinements);
  return out;
}
} // namespace breastsim::scan
