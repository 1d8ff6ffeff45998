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

PointLocation locate_points(const dolfinx::mesh::Mesh& mesh, std::span<const double> points)
{
  namespace geo = dolfinx::geometry;
  const auto& geometry = mesh.geometry();
  const auto& x_dofmap = geometry.dofmap();
  const auto xg = geometry.x();
  const auto& cmap = geometry.cmap();
  const std::int32_t ncells = mesh.topology().index_map(3)->size_local();
  const std::size_t num_nodes = x_dofmap.num_links(0);

  // Coordinates of every cell's geometry nodes, and the padding of the
  // vertices' bounding boxes: a curved face bulges out of its vertices' box
  // by at most its sagitta, far less than an eighth of the cell's size; and
  // points just outside the mesh (a finer mesh's skin nodes) still find the
  // cells next to them as candidates.
  std::vector<double> nodes(static_cast<std::size_t>(ncells) * num_nodes * 3);
  double size = 0;
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    auto dofs = x_dofmap.links(c);
    std::array<double, 3> lo = {1e300, 1e300, 1e300}, hi = {-1e300, -1e300, -1e300};
    for (std::size_t i = 0; i < num_nodes; ++i)
      for (int d = 0; d < 3; ++d)
      {
        const double v = xg[3 * dofs[i] + d];
        nodes[(c * num_nodes + i) * 3 + d] = v;
        lo[d] = std::min(lo[d], v);
        hi[d] = std::max(hi[d], v);
      }
    size = std::max({size, hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  }
  auto cell_nodes = [&](std::int32_t c)
  { return std::span<const double>(nodes.data() + c * num_nodes * 3, num_nodes * 3); };

  // Whether each cell's geometry is affine: every edge node at its edge's
  // midpoint (a P2 mesh's interior cells; only cells on the curved skin are
  // not), where the vertices' affine pull-back is exact.
  std::vector<char> affine(ncells, 1);
  if (!cmap.is_affine())
  {
    const double tol = 1e-10 * size;
    const auto layout = cmap.create_dof_layout();
    const auto v = dolfinx::mesh::get_entity_vertices(dolfinx::mesh::CellType::tetrahedron, 1);
    for (std::int32_t c = 0; c < ncells; ++c)
    {
      auto nc = cell_nodes(c);
      for (int e = 0; e < 6 && affine[c]; ++e)
      {
        const auto& edge_nodes = layout.entity_dofs(1, e);
        for (int node : edge_nodes)
          for (int d = 0; d < 3; ++d)
            if (std::abs(nc[3 * node + d] - 0.5 * (nc[3 * v.links(e)[0] + d] + nc[3 * v.links(e)[1] + d])) > tol)
              affine[c] = 0;
      }
    }
  }

  std::vector<std::int32_t> all(ncells);
  std::iota(all.begin(), all.end(), 0);
  geo::BoundingBoxTree tree(mesh, 3, all, size / 8);
  const auto candidates = geo::compute_collisions(tree, points);

  const std::size_t n = points.size() / 3;
  PointLocation loc;
  loc.cells.assign(n, -1);
  loc.points.assign(points.begin(), points.end());
  loc.reference.assign(3 * n, 0.0);
  std::vector<std::pair<double, std::int32_t>> curved; // (affine estimate's outside, cell)
  for (std::size_t p = 0; p < n; ++p)
  {
    std::span<const double, 3> x(points.data() + 3 * p, 3);
    std::array<double, 3> best_X = {0.25, 0.25, 0.25};
    double best = std::numeric_limits<double>::infinity();
    std::int32_t best_cell = -1;
    auto consider = [&](std::int32_t c, const std::array<double, 3>& X)
    {
      const double o = outside(X);
      if (o < best)
      {
        best = o;
        best_X = X;
        best_cell = c;
      }
    };
    // Affine cells first (exact and cheap), then the curved candidates in
    // the order of their affine estimate, by Newton, until one holds x.
    curved.clear();
    for (const std::int32_t c : candidates.links(p))
    {
      std::array<double, 3> X;
      if (!affine_pull_back(cell_nodes(c), x, X))
        continue;
      if (affine[c])
      {
        consider(c, X);
        if (best == 0)
          break;
      }
      else if (outside(X) <= 0.5)
        curved.push_back({outside(X), c});
    }
    std::sort(curved.begin(), curved.end());
    for (std::size_t k = 0; k < curved.size() && best > 0; ++k)
    {
      std::array<double, 3> X;
      if (pull_back(cmap, cell_nodes(curved[k].second), x, X))
        consider(curved[k].second, X);
    }
    if (best_cell < 0)
    {
      // Outside every padded box: the cell with the nearest centroid.
      ++loc.far;
      double dmin = std::numeric_limits<double>::infinity();
      for (std::int32_t c = 0; c < ncells; ++c)
      {
        auto nc = cell_nodes(c);
        double d2 = 0;
        for (int d = 0; d < 3; ++d)
        {
          const double m = 0.25 * (nc[d] + nc[3 + d] + nc[6 + d] + nc[9 + d]) - x[d];
          d2 += m * m;
        }
        if (d2 < dmin)
        {
          dmin = d2;
          best_cell = c;
        }
      }
      std::array<double, 3> X;
      best_X = {0.25, 0.25, 0.25};
      if (pull_back(cmap, cell_nodes(best_cell), x, X))
        best_X = X;
    }
    loc.cells[p] = best_cell;
    if (best > 0 && project_to_reference_tetrahedron(best_X) > 0)
    {
      ++loc.moved;
      const auto y = push_forward(cmap, cell_nodes(best_cell), best_X);
      std::copy(y.begin(), y.end(), loc.points.begin() + 3 * p);
    }
    std::copy(best_X.begin(), best_X.end(), loc.reference.begin() + 3 * p);
  }
  return loc;
}
} // namespace breastsim
