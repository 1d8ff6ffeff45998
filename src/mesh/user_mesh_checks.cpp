// SPDX-License-Identifier: LGPL-3.0-or-later
#include "user_mesh_checks.hpp"
#include "errors.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>

namespace breastsim::meshes
{
namespace
{
using Vec3 = std::array<double, 3>;

Vec3 node(const TaggedMesh& m, std::int64_t n) { return {m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]}; }
Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
std::string point(const Vec3& p) { return fmt::format("({:.6g}, {:.6g}, {:.6g}) m", p[0], p[1], p[2]); }

std::string surface_name(int tag, const UserMeshOrigin& o)
{
  return tag == o.base ? "base" : tag == o.skin ? "skin" : tag == o.symmetry ? "symmetry" : "?";
}

/// Largest side of the nodes' bounding box.
double extent(const TaggedMesh& m)
{
  double e = 0;
  for (int i = 0; i < 3; ++i)
  {
    double lo = m.x[i], hi = m.x[i];
    for (std::size_t n = 0; n < m.num_nodes(); ++n)
    {
      lo = std::min(lo, m.x[3 * n + i]);
      hi = std::max(hi, m.x[3 * n + i]);
    }
    e = std::max(e, hi - lo);
  }
  return e;
}

/// Finite coordinates in metres: a breast spans well under 1 m (a mesh
/// written in millimetres spans about 100).
void check_units(const TaggedMesh& m, const UserMeshOrigin& o)
{
  for (std::size_t n = 0; n < m.num_nodes(); ++n)
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(m.x[3 * n + i]))
        throw InputError(fmt::format("{}: node {} has a non-finite coordinate {}", o.where, n, m.x[3 * n + i]));
  const double e = extent(m);
  if (e >= 1.0)
    throw InputError(fmt::format("{}: the mesh spans {:.4g} m; coordinates are in metres (docs/MODEL.md) and a "
                                 "breast spans less than 1 m (a mesh in millimetres? scale it by 0.001)",
                                 o.where, e));
}

/// Signed volume of the corners: V = (b - a) . ((c - a) x (d - a)) / 6,
/// positive for gmsh's ordering of a tetrahedron's nodes.
double corner_volume(const TaggedMesh& m, std::size_t c)
{
  const std::int64_t* v = &m.cells[c * m.nodes_per_cell()];
  const Vec3 a = node(m, v[0]);
  return dot(sub(node(m, v[1]), a), cross(sub(node(m, v[2]), a), sub(node(m, v[3]), a))) / 6;
}

double longest_edge(const TaggedMesh& m, std::size_t c)
{
  const std::int64_t* v = &m.cells[c * m.nodes_per_cell()];
  double L = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
    {
      const Vec3 d = sub(node(m, v[i]), node(m, v[j]));
      L = std::max(L, std::sqrt(dot(d, d)));
    }
  return L;
}

/// Every tetrahedron positively oriented and not flat: V > 1e-8 L^3 (a
/// regular tetrahedron has V = L^3 / (6 sqrt 2) ~ 0.118 L^3).
void check_cell_volumes(const TaggedMesh& m, const UserMeshOrigin& o)
{
  for (std::size_t c = 0; c < m.num_cells(); ++c)
  {
    const double V = corner_volume(m, c), L = longest_edge(m, c);
    if (!(V > 1e-8 * L * L * L))
      throw InputError(fmt::format(
          "{}: physical volume \"tissue\": tetrahedron {} (gmsh element {}) is {}: signed volume {:.6g} "
          "m^3, longest edge {:.4g} m; every tetrahedron needs a volume above 1e-8 (longest edge)^3 "
          "with its corners in gmsh's (positive) order",
          o.where, c, o.cell_elements[c], V < 0 ? "inverted" : "degenerate", V, L));
  }
}

/// Node 4 + k of gmsh's 10-node tetrahedron lies on edge k.
constexpr int tet10_edges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {2, 3}, {1, 3}};

/// det J of the quadratic map x(xi) = sum_a x_a N_a(xi) at barycentric
/// coordinates l: corners N_a = l_a (2 l_a - 1), edges N_ij = 4 l_i l_j,
/// with grad l_0 = (-1, -1, -1), grad l_k = e_k.
double p2_det_jacobian(const std::array<Vec3, 10>& x, const std::array<double, 4>& l)
{
  const Vec3 dl[4] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Vec3 J[3] = {}; // J[i][j] = dx_i / dxi_j
  auto add = [&](const Vec3& xa, const Vec3& g)
  {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        J[i][j] += xa[i] * g[j];
  };
  for (int a = 0; a < 4; ++a)
    add(x[a], {(4 * l[a] - 1) * dl[a][0], (4 * l[a] - 1) * dl[a][1], (4 * l[a] - 1) * dl[a][2]});
  for (int k = 0; k < 6; ++k)
  {
    const int i = tet10_edges[k][0], j = tet10_edges[k][1];
    Vec3 g;
    for (int d = 0; d < 3; ++d)
      g[d] = 4 * (l[j] * dl[i][d] + l[i] * dl[j][d]);
    add(x[4 + k], g);
  }
  return dot(J[0], cross(J[1], J[2]));
}

/// 10-node tetrahedra: det J > 1e-8 (6 V) at each of the ten nodes (for
/// straight edges det J = 6 V everywhere), i.e. the curved cell does not fold.
void check_curved_cells(const TaggedMesh& m, const UserMeshOrigin& o)
{
  if (m.order != 2)
    return;
  std::array<std::array<double, 4>, 10> at{};
  for (int a = 0; a < 4; ++a)
    at[a][a] = 1;
  for (int k = 0; k < 6; ++k)
    at[4 + k][tet10_edges[k][0]] = at[4 + k][tet10_edges[k][1]] = 0.5;
  for (std::size_t c = 0; c < m.num_cells(); ++c)
  {
    std::array<Vec3, 10> x;
    for (int a = 0; a < 10; ++a)
      x[a] = node(m, m.cells[10 * c + a]);
    const double six_volume = 6 * corner_volume(m, c);
    for (int k = 0; k < 10; ++k)
      if (const double d = p2_det_jacobian(x, at[k]); !(d > 1e-8 * six_volume))
        throw InputError(fmt::format(
            "{}: physical volume \"tissue\": curved tetrahedron {} (gmsh element {}) folds: det J = "
            "{:.4g} m^3 at its node {} {} (6 x its corners' volume: {:.4g} m^3); det J must stay "
            "positive (mid-edge nodes too far from the edges' midpoints)",
            o.where, c, o.cell_elements[c], d, k, point(x[k]), six_volume));
  }
}

/// A face of a cell (owner >= 0) or a tagged facet (owner = -1 - facet),
/// by its sorted corner nodes; `opposite`: the cell's node off the face.
struct Face
{
  std::array<std::int64_t, 3> corners;
  std::int64_t owner;
  std::int64_t opposite;
};

/// The cell on the inner side of each tagged facet and its node off the facet.
struct FacetSide
{
  std::int64_t cell = -1;
  std::int64_t opposite = -1;
};

std::vector<Face> all_faces(const TaggedMesh& m)
{
  std::vector<Face> faces;
  faces.reserve(4 * m.num_cells() + m.facet_tags.size());
  for (std::size_t c = 0; c < m.num_cells(); ++c)
  {
    const std::int64_t* v = &m.cells[c * m.nodes_per_cell()];
    for (int off = 0; off < 4; ++off)
    {
      Face f{{}, std::int64_t(c), v[off]};
      for (int k = 0, j = 0; k < 4; ++k)
        if (k != off)
          f.corners[j++] = v[k];
      std::sort(f.corners.begin(), f.corners.end());
      faces.push_back(f);
    }
  }
  for (std::size_t f = 0; f < m.facet_tags.size(); ++f)
  {
    const std::int64_t* v = &m.facets[f * m.nodes_per_facet()];
    Face face{{v[0], v[1], v[2]}, -1 - std::int64_t(f), -1};
    std::sort(face.corners.begin(), face.corners.end());
    faces.push_back(face);
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b)
            { return a.corners != b.corners ? a.corners < b.corners : a.owner > b.owner; });
  return faces;
}

std::string corners_text(const TaggedMesh& m, const Face& f)
{
  return point(node(m, f.corners[0])) + ", " + point(node(m, f.corners[1])) + ", " +
         point(node(m, f.corners[2]));
}

/// One face's run: the cells (sorted first) and tagged facets that share it.
void match_run(const TaggedMesh& m, const UserMeshOrigin& o, const Face* run, std::size_t n,
               std::vector<FacetSide>& sides)
{
  std::size_t cells = 0;
  while (cells < n && run[cells].owner >= 0)
    ++cells;
  const std::size_t facets = n - cells;
  auto facet = [&](std::size_t k) { return std::size_t(-1 - run[cells + k].owner); };
  auto group = [&](std::size_t k) { return surface_name(m.facet_tags[facet(k)], o); };
  if (cells > 2)
    throw InputError(fmt::format("{}: the face with corners {} is shared by {} tetrahedra (first {}, {}, {}): "
                                 "the mesh is not a conforming tetrahedral mesh",
                                 o.where, corners_text(m, run[0]), cells, run[0].owner, run[1].owner, run[2].owner));
  if (cells == 1 && facets == 0)
    throw InputError(fmt::format("{}: a boundary face of tetrahedron {} (gmsh element {}), corners {}, is in "
                                 "none of the surfaces \"base\", \"skin\", \"symmetry\"; every boundary "
                                 "face must belong to one of them",
                                 o.where, run[0].owner, o.cell_elements[run[0].owner], corners_text(m, run[0])));
  if (facets > 1)
    throw InputError(fmt::format("{}: surface \"{}\" (gmsh element {}) and surface \"{}\" (gmsh element {}) hold "
                                 "the same triangle, corners {}; a boundary face belongs to one surface only",
                                 o.where, group(0), o.facet_elements[facet(0)], group(1),
                                 o.facet_elements[facet(1)], corners_text(m, run[0])));
  if (facets == 1 && cells != 1)
    throw InputError(fmt::format("{}: surface \"{}\": triangle (gmsh element {}), corners {}, {}", o.where, group(0),
                                 o.facet_elements[facet(0)], corners_text(m, run[0]),
                                 cells == 0 ? "is not a face of any tetrahedron of \"tissue\""
                                            : "lies inside the body (a face of two tetrahedra); the surfaces "
                                              "must be on the boundary"));
  if (facets == 1)
    sides[facet(0)] = {run[0].owner, run[0].opposite};
}

/// Each tagged facet is a boundary face of one cell; each boundary face is tagged once.
std::vector<FacetSide> match_faces(const TaggedMesh& m, const UserMeshOrigin& o)
{
  const std::vector<Face> faces = all_faces(m);
  std::vector<FacetSide> sides(m.facet_tags.size());
  for (std::size_t b = 0, e = 0; b < faces.size(); b = e)
  {
    while (e < faces.size() && faces[e].corners == faces[b].corners)
      ++e;
    match_run(m, o, &faces[b], e - b, sides);
  }
  return sides;
}

/// The facets of surface `tag` on the plane X_axis = 0 (every node within
/// `tol`), facing -e_axis: n . e_axis < 0 for the outward normal
/// n = (b - a) x (c - a), turned away from the cell's node off the facet.
void check_plane_surface(const TaggedMesh& m, const UserMeshOrigin& o, const std::vector<FacetSide>& sides,
                         int tag, int axis, double tol)
{
  const std::string name = surface_name(tag, o), ax(1, "xyz"[axis]);
  const std::size_t npf = m.nodes_per_facet();
  for (std::size_t f = 0; f < m.facet_tags.size(); ++f)
  {
    if (m.facet_tags[f] != tag)
      continue;
    const std::int64_t* v = &m.facets[f * npf];
    for (std::size_t k = 0; k < npf; ++k)
      if (const Vec3 p = node(m, v[k]); std::abs(p[axis]) > tol)
        throw InputError(fmt::format("{}: surface \"{}\": node {} of triangle (gmsh element {}) is off the plane "
                                     "{} = 0 (|{}| > {:.3g} m); the {} face lies on {} = 0 (docs/MODEL.md)",
                                     o.where, name, point(p), o.facet_elements[f], ax, ax, tol, name, ax));
    const Vec3 a = node(m, v[0]);
    Vec3 n = cross(sub(node(m, v[1]), a), sub(node(m, v[2]), a));
    if (dot(n, sub(node(m, sides[f].opposite), a)) > 0)
      n = {-n[0], -n[1], -n[2]};
    const double len = std::sqrt(dot(n, n));
    if (!(n[axis] < -0.5 * len))
      throw InputError(fmt::format(
          "{}: surface \"{}\": triangle (gmsh element {}) of tetrahedron {} has the outward normal "
          "({:.3g}, {:.3g}, {:.3g}); the body lies in {} >= 0, so the {} face must face -{} (a mirrored mesh?)",
          o.where, name, o.facet_elements[f], sides[f].cell, n[0] / len + 0.0, n[1] / len + 0.0, n[2] / len + 0.0, ax,
          name, ax)); // + 0.0: no "-0"
  }
}

/// The body in y >= 0 (in front of the chest) and, for a half model, x >= 0.
void check_half_space(const TaggedMesh& m, const UserMeshOrigin& o, double tol)
{
  for (std::size_t n = 0; n < m.num_nodes(); ++n)
    for (int axis : {0, 1})
      if (m.x[3 * n + axis] < -tol && (axis == 1 || o.half))
        throw InputError(fmt::format("{}: node {} at {} has {} < 0; {} (docs/MODEL.md)", o.where, n, point(node(m, n)),
                                     axis == 0 ? "x" : "y",
                                     o.half ? "the half model lies in x >= 0 and in front of the chest, y >= 0"
                                            : "the breast lies in front of the chest, y >= 0"));
}
} // namespace

void check_user_mesh(const TaggedMesh& m, const UserMeshOrigin& o)
{
  check_units(m, o);
  check_cell_volumes(m, o);
  check_curved_cells(m, o);
  const std::vector<FacetSide> sides = match_faces(m, o);
  // Plane tolerance: relative to the size of the body.
  const double tol = 1e-6 * extent(m);
  if (o.half)
    check_plane_surface(m, o, sides, o.symmetry, 0, tol);
  check_plane_surface(m, o, sides, o.base, 1, tol);
  check_half_space(m, o, tol);
}
} // namespace breastsim::meshes
