// SPDX-License-Identifier: LGPL-3.0-or-later
#include "point_location.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/CoordinateElement.h>
#include <dolfinx/geometry/BoundingBoxTree.h>
#include <dolfinx/geometry/utils.h>
#include <dolfinx/mesh/cell_types.h>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace breastsim
{
namespace
{
/// X = K (x - x0) with J = [x1 - x0, x2 - x0, x3 - x0] the vertices' edge
/// matrix (the affine map of the cell's vertices).
bool affine_pull_back(std::span<const double> nodes, std::span<const double, 3> x,
                      std::span<double, 3> X)
{
  double J[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      J[i][j] = nodes[3 * (j + 1) + i] - nodes[i];
  const double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1])
                     - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0])
                     + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
  if (!(std::abs(det) > 0))
    return false;
  // K = J^-1 = adj(J) / det
  const double K[3][3] = {
      {(J[1][1] * J[2][2] - J[1][2] * J[2][1]) / det, (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / det,
       (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / det},
      {(J[1][2] * J[2][0] - J[1][0] * J[2][2]) / det, (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / det,
       (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / det},
      {(J[1][0] * J[2][1] - J[1][1] * J[2][0]) / det, (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / det,
       (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / det}};
  for (int i = 0; i < 3; ++i)
    X[i] = K[i][0] * (x[0] - nodes[0]) + K[i][1] * (x[1] - nodes[1]) + K[i][2] * (x[2] - nodes[2]);
  return true;
}

/// How far X lies outside the reference tetrahedron (0 inside), in the
/// largest violated barycentric coordinate.
double outside(std::span<const double, 3> X)
{
  const double o = std::max({0.0, -X[0], -X[1], -X[2], X[0] + X[1] + X[2] - 1.0});
  return o > 1e-12 ? o : 0.0; // round-off of a point on a face or vertex: inside
}

/// x = sum_i phi_i(X) x_i: the physical point of reference point X.
std::array<double, 3> push_forward(const dolfinx::fem::CoordinateElement& cmap,
                                   std::span<const double> nodes, std::span<const double, 3> X)
{
  const auto shape = cmap.tabulate_shape(0, 1);
  std::vector<double> phi(shape[0] * shape[1] * shape[2] * shape[3]);
  cmap.tabulate(0, std::span<const double>(X.data(), 3), {1, 3}, phi);
  std::array<double, 3> x = {0, 0, 0};
  const std::size_t num_nodes = nodes.size() / 3;
  for (std::size_t i = 0; i < num_nodes; ++i)
    for (int d = 0; d < 3; ++d)
      x[d] += phi[i] * nodes[3 * i + d];
  return x;
}
} // namespace

bool pull_back(const dolfinx::fem::CoordinateElement& cmap, std::span<const double> nodes,
               std::span<const double, 3> x, std::span<double, 3> X)
{
  if (!affine_pull_back(nodes, x, X))
    return false;
  if (cmap.is_affine())
    return true;
  // Curved cell: Newton on x(X) = x, only where the vertices' affine map
  // puts the point near the cell (else the iteration may not converge and
  // the cell is not a candidate anyway).
  if (outside(X) > 0.5)
    return false;
  namespace stdex = std::experimental;
  using cmdspan2 = stdex::mdspan<const double, stdex::dextents<std::size_t, 2>>;
  using mdspan2 = stdex::mdspan<double, stdex::dextents<std::size_t, 2>>;
  try
  {
    cmap.pull_back_nonaffine(mdspan2(X.data(), 1, 3), cmdspan2(x.data(), 1, 3),
                             cmdspan2(nodes.data(), nodes.size() / 3, 3), 1e-12, 20);
  }
  catch (const std::runtime_error&)
  {
    return false;
  }
  return std::isfinite(X[0]) && std::isfinite(X[1]) && std::isfinite(X[2]);
}

// Euclidean projection onto the simplex {X >= 0, sum X <= 1}: clamping
// suffices when the clamped point has sum <= 1; otherwise the nearest point
// lies on the face sum X = 1, i.e. the projection onto the probability
// simplex: X_i = max(X_i - t, 0) with t chosen so that the sum is 1
// (sort-based, Held et al.).
double project_to_reference_tetrahedron(std::span<double, 3> X)
{
  const std::array<double, 3> X0 = {X[0], X[1], X[2]};
  std::array<double, 3> c;
  for (int i = 0; i < 3; ++i)
    c[i] = std::max(X[i], 0.0);
  if (c[0] + c[1] + c[2] > 1.0)
  {
    std::array<double, 3> s = X0;
    std::sort(s.rbegin(), s.rend());
    double cum = 0, t = 0;
    for (int k = 0; k < 3; ++k)
    {
      cum += s[k];
      const double tk = (cum - 1.0) / (k + 1);
      if (s[k] - tk > 0)
        t = tk;
    }
    for (int i = 0; i < 3; ++i)
      c[i] = std::max(X0[i] - t, 0.0);
  }
  double d2 = 0;
  for (int i = 0; i < 3; ++i)
  {
    d2 += (c[i] - X0[i]) * (c[i] - X0[i]);
    X[i] = c[i];
  }
  return std::sqrt(d2);
}

namespace
{
/// Every local cell's geometry nodes (coordinates, cell-major), the largest
/// cell extent, and whether each cell's geometry is affine.
struct CellNodes
{
  std::vector<double> x;
  std::size_t per_cell = 0;
  double size = 0;
  std::vector<char> affine;
  std::span<const double> cell(std::int32_t c) const
  {
    return std::span<const double>(x.data() + c * per_cell * 3, per_cell * 3);
  }
  std::int32_t num_cells() const { return static_cast<std::int32_t>(affine.size()); }
};

CellNodes gather_cell_nodes(const dolfinx::mesh::Mesh& mesh)
{
  const auto& x_dofmap = mesh.geometry().dofmap();
  const auto xg = mesh.geometry().x();
  const std::int32_t ncells = mesh.topology().index_map(3)->size_local();
  CellNodes g;
  g.per_cell = x_dofmap.num_links(0);
  g.x.resize(static_cast<std::size_t>(ncells) * g.per_cell * 3);
  g.affine.assign(ncells, 1);
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    auto dofs = x_dofmap.links(c);
    std::array<double, 3> lo = {1e300, 1e300, 1e300}, hi = {-1e300, -1e300, -1e300};
    for (std::size_t i = 0; i < g.per_cell; ++i)
      for (int d = 0; d < 3; ++d)
      {
        const double v = xg[3 * dofs[i] + d];
        g.x[(c * g.per_cell + i) * 3 + d] = v;
        lo[d] = std::min(lo[d], v);
        hi[d] = std::max(hi[d], v);
      }
    g.size = std::max({g.size, hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  }
  return g;
}

/// Mark the cells whose geometry is not affine: an edge node off its edge's
/// midpoint (a P2 mesh's cells on the curved skin). In affine cells the
/// vertices' affine pull-back is exact.
void mark_curved_cells(CellNodes& g, const dolfinx::fem::CoordinateElement& cmap)
{
  if (cmap.is_affine())
    return;
  const double tol = 1e-10 * g.size;
  const auto layout = cmap.create_dof_layout();
  const auto v = dolfinx::mesh::get_entity_vertices(dolfinx::mesh::CellType::tetrahedron, 1);
  for (std::int32_t c = 0; c < g.num_cells(); ++c)
  {
    auto nc = g.cell(c);
    for (int e = 0; e < 6 && g.affine[c]; ++e)
      for (int node : layout.entity_dofs(1, e))
        for (int d = 0; d < 3; ++d)
          if (std::abs(nc[3 * node + d] - 0.5 * (nc[3 * v.links(e)[0] + d] + nc[3 * v.links(e)[1] + d]))
              > tol)
            g.affine[c] = 0;
  }
}

/// The best cell found for one point: its reference point X and the gap,
/// how far X lies outside the reference tetrahedron (0: inside).
struct Found
{
  std::int32_t cell = -1;
  std::array<double, 3> X = {0.25, 0.25, 0.25};
  double gap = std::numeric_limits<double>::infinity();
  void consider(std::int32_t c, const std::array<double, 3>& Xc)
  {
    if (const double o = outside(Xc); o < gap)
    {
      gap = o;
      X = Xc;
      cell = c;
    }
  }
};

/// Affine candidates first (exact and cheap), then the curved ones in the
/// order of their affine estimate, by Newton, until one holds x.
Found search_candidates(const CellNodes& g, const dolfinx::fem::CoordinateElement& cmap,
                        std::span<const std::int32_t> candidates, std::span<const double, 3> x)
{
  Found f;
  std::vector<std::pair<double, std::int32_t>> curved; // (affine estimate's outside, cell)
  for (const std::int32_t c : candidates)
  {
    std::array<double, 3> X;
    if (!affine_pull_back(g.cell(c), x, X))
      continue;
    if (g.affine[c])
    {
      f.consider(c, X);
      if (f.gap == 0)
        return f;
    }
    else if (outside(X) <= 0.5)
      curved.push_back({outside(X), c});
  }
  std::sort(curved.begin(), curved.end());
  for (std::size_t k = 0; k < curved.size() && f.gap > 0; ++k)
  {
    std::array<double, 3> X;
    if (pull_back(cmap, g.cell(curved[k].second), x, X))
      f.consider(curved[k].second, X);
  }
  return f;
}

/// The cell with the nearest vertex centroid |(x_0 + .. + x_3)/4 - x|, for a
/// point outside every padded box, with its pull-back if Newton converges.
Found nearest_cell(const CellNodes& g, const dolfinx::fem::CoordinateElement& cmap,
                   std::span<const double, 3> x)
{
  Found f;
  double dmin = std::numeric_limits<double>::infinity();
  for (std::int32_t c = 0; c < g.num_cells(); ++c)
  {
    auto nc = g.cell(c);
    double d2 = 0;
    for (int d = 0; d < 3; ++d)
    {
      const double m = 0.25 * (nc[d] + nc[3 + d] + nc[6 + d] + nc[9 + d]) - x[d];
      d2 += m * m;
    }
    if (d2 < dmin)
    {
      dmin = d2;
      f.cell = c;
    }
  }
  std::array<double, 3> X;
  if (pull_back(cmap, g.cell(f.cell), x, X))
    f.X = X;
  return f;
}
} // namespace

PointLocation locate_points(const dolfinx::mesh::Mesh& mesh, std::span<const double> points)
{
  const auto& cmap = mesh.geometry().cmap();
  CellNodes g = gather_cell_nodes(mesh);
  mark_curved_cells(g, cmap);
  // Candidates from the vertices' bounding boxes, padded: a curved face
  // bulges out of its vertices' box by at most its sagitta, far less than
  // an eighth of the cell's size; and points just outside the mesh (a finer
  // mesh's skin nodes) still find the cells next to them.
  std::vector<std::int32_t> all(g.num_cells());
  std::iota(all.begin(), all.end(), 0);
  dolfinx::geometry::BoundingBoxTree tree(mesh, 3, all, g.size / 8);
  const auto candidates = dolfinx::geometry::compute_collisions(tree, points);

  const std::size_t n = points.size() / 3;
  PointLocation loc;
  loc.cells.assign(n, -1);
  loc.points.assign(points.begin(), points.end());
  loc.reference.assign(3 * n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
  {
    std::span<const double, 3> x(points.data() + 3 * p, 3);
    Found f = search_candidates(g, cmap, candidates.links(p), x);
    if (f.cell < 0)
    {
      ++loc.far;
      f = nearest_cell(g, cmap, x);
    }
    loc.cells[p] = f.cell;
    if (f.gap > 0 && project_to_reference_tetrahedron(f.X) > 0)
    {
      ++loc.moved;
      const auto y = push_forward(cmap, g.cell(f.cell), f.X);
      std::copy(y.begin(), y.end(), loc.points.begin() + 3 * p);
    }
    std::copy(f.X.begin(), f.X.end(), loc.reference.begin() + 3 * p);
  }
  return loc;
}
} // namespace breastsim
