// SPDX-License-Identifier: LGPL-3.0-or-later
// Point location in meshes of any geometry order (src/mesh/point_location.hpp):
// the projection onto the reference tetrahedron, the curved-cell pull-back,
// and locate_points on P1 and curved P2 meshes of the half cap.
#include "fixtures.hpp"
#include "point_location.hpp"
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/CoordinateElement.h>
#include <gtest/gtest.h>

using namespace breastsim;

TEST(PointLocation, ProjectionOntoTheReferenceTetrahedron)
{
  struct Case
  {
    std::array<double, 3> X, expected;
  };
  const Case cases[] = {
      {{0.2, 0.3, 0.1}, {0.2, 0.3, 0.1}},    // inside: unchanged
      {{-0.5, 0.3, 0.2}, {0.0, 0.3, 0.2}},   // beyond the face X0 = 0
      {{-1, -2, -3}, {0, 0, 0}},             // beyond the vertex 0
      {{1.0, 1.0, 0.0}, {0.5, 0.5, 0.0}},    // beyond the edge between vertices 1 and 2
      {{0.5, 0.5, 0.5}, {1 / 3.0, 1 / 3.0, 1 / 3.0}}, // beyond the face sum = 1
      {{3.0, 0.0, 0.0}, {1.0, 0.0, 0.0}},    // beyond the vertex 1
      {{0.9, 0.4, -0.2}, {0.75, 0.25, 0.0}}, // beyond the edge on the face X2 = 0
  };
  for (const auto& c : cases)
  {
    std::array<double, 3> X = c.X;
    const double moved = project_to_reference_tetrahedron(X);
    double d2 = 0;
    for (int i = 0; i < 3; ++i)
    {
      EXPECT_NEAR(X[i], c.expected[i], 1e-14) << "point (" << c.X[0] << ", " << c.X[1] << ", " << c.X[2] << ")";
      d2 += (c.X[i] - c.expected[i]) * (c.X[i] - c.expected[i]);
    }
    EXPECT_NEAR(moved, std::sqrt(d2), 1e-14);
  }
}

namespace
{
/// Coordinates of the geometry nodes of local cell c (num_nodes x 3).
std::vector<double> cell_nodes(const dolfinx::mesh::Mesh& mesh, std::int32_t c)
{
  auto dofs = mesh.geometry().dofmap().links(c);
  const auto x = mesh.geometry().x();
  std::vector<double> nodes;
  for (auto d : dofs)
    nodes.insert(nodes.end(), x.begin() + 3 * d, x.begin() + 3 * d + 3);
  return nodes;
}

/// The physical point of reference point X in a cell with nodes `nodes`.
std::array<double, 3> push_forward(const dolfinx::fem::CoordinateElement& cmap,
                                   const std::vector<double>& nodes, const std::array<double, 3>& X)
{
  const auto shape = cmap.tabulate_shape(0, 1);
  std::vector<double> phi(shape[2]);
  cmap.tabulate(0, X, {1, 3}, phi);
  std::array<double, 3> x = {0, 0, 0};
  for (std::size_t i = 0; i < shape[2]; ++i)
    for (int d = 0; d < 3; ++d)
      x[d] += phi[i] * nodes[3 * i + d];
  return x;
}
} // namespace

TEST(PointLocation, PullBackInvertsTheCurvedMapOfEveryCell)
{
  // P2 half cap: skin cells are curved. For reference points spread over
  // each cell, x = F(X) and pull_back(x) must return X.
  auto mesh = build_neutral_mesh(fixtures::coarse_case(2, 0.016), MPI_COMM_SELF).mesh;
  const auto& cmap = mesh->geometry().cmap();
  ASSERT_FALSE(cmap.is_affine());
  const std::int32_t ncells = mesh->topology().index_map(3)->size_local();
  const std::array<double, 3> refs[] = {{0.25, 0.25, 0.25}, {0.1, 0.2, 0.6}, {0.7, 0.1, 0.1}, {0.0, 0.5, 0.5}};
  double worst = 0;
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    const auto nodes = cell_nodes(*mesh, c);
    for (const auto& X0 : refs)
    {
      const auto x = push_forward(cmap, nodes, X0);
      std::array<double, 3> X;
      ASSERT_TRUE(pull_back(cmap, nodes, x, X)) << "cell " << c;
      for (int i = 0; i < 3; ++i)
        worst = std::max(worst, std::abs(X[i] - X0[i]));
    }
  }
  EXPECT_LT(worst, 1e-10);
}

TEST(PointLocation, LocatesPointsInP1AndCurvedP2Meshes)
{
  for (int order : {1, 2})
  {
    auto mesh = build_neutral_mesh(fixtures::coarse_case(order, 0.016), MPI_COMM_SELF).mesh;
    const auto& cmap = mesh->geometry().cmap();
    const std::int32_t ncells = mesh->topology().index_map(3)->size_local();
    // One point inside every cell (its reference centroid's image), and
    // the same points pushed 1 mm along +x/+y beyond the skin for the
    // cells' first node: a handful lands outside the mesh.
    std::vector<double> points;
    for (std::int32_t c = 0; c < ncells; ++c)
    {
      const auto x = push_forward(cmap, cell_nodes(*mesh, c), {0.25, 0.25, 0.25});
      points.insert(points.end(), x.begin(), x.end());
    }
    const std::vector<double> outside = {0.0, 0.06 + 0.001, 0.0,  // above the nipple (0, H, 0)
                                         0.0, 0.03, -0.06}; // 2 mm below the skin at y = 30 mm
    points.insert(points.end(), outside.begin(), outside.end());
    const PointLocation loc = locate_points(*mesh, points);
    ASSERT_EQ(loc.cells.size(), points.size() / 3);
    for (std::int32_t c = 0; c < ncells; ++c)
    {
      // A centroid lies in its own cell only (cells do not overlap), at X = 1/4.
      EXPECT_EQ(loc.cells[c], c) << "P" << order << " cell " << c;
      for (int i = 0; i < 3; ++i)
      {
        EXPECT_NEAR(loc.reference[3 * c + i], 0.25, 1e-9);
        EXPECT_DOUBLE_EQ(loc.points[3 * c + i], points[3 * c + i]);
      }
    }
    EXPECT_EQ(loc.moved, 2u) << "P" << order;
    // The moved points lie in their cell (reference point in the
    // tetrahedron) and close to where they were.
    for (std::size_t p = ncells; p < points.size() / 3; ++p)
    {
      const double* X = &loc.reference[3 * p];
      EXPECT_GE(std::min({X[0], X[1], X[2]}), 0.0);
      EXPECT_LE(X[0] + X[1] + X[2], 1.0 + 1e-14);
      const auto y = push_forward(cmap, cell_nodes(*mesh, loc.cells[p]), {X[0], X[1], X[2]});
      double d2 = 0;
      for (int i = 0; i < 3; ++i)
      {
        EXPECT_NEAR(y[i], loc.points[3 * p + i], 1e-12);
        d2 += (y[i] - points[3 * p + i]) * (y[i] - points[3 * p + i]);
      }
      EXPECT_LT(std::sqrt(d2), 0.02) << "P" << order << " outside point " << p - ncells;
      EXPECT_GT(std::sqrt(d2), 0.0005);
    }
  }
}
