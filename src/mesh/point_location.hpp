// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Locating points in the cells of a mesh of any geometry order, for
// evaluating a Function there (transfer between non-matching meshes).
//
// dolfinx 0.5's compute_colliding_cells decides with GJK on the cell's
// vertices, which is exact only for affine cells and stops with "GJK error:
// max iteration limit reached" on curved (P2) cells. Here a cell is accepted
// by pulling the point back to the reference tetrahedron: affine cells by
// the inverse Jacobian, curved ones by the coordinate element's Newton
// pull-back, among the cells whose (padded) bounding box holds the point.
#include <cstdint>
#include <dolfinx/mesh/Mesh.h>
#include <span>
#include <vector>

namespace breastsim
{
struct PointLocation
{
  /// Cell of every point (local index).
  std::vector<std::int32_t> cells;
  /// The points (row-major n x 3), each moved into its cell: unchanged when
  /// inside, else the image of the nearest point of the reference
  /// tetrahedron (so that values are never extrapolated).
  std::vector<double> points;
  /// Reference coordinates of every (moved) point in its cell (n x 3).
  std::vector<double> reference;
  /// How many points were inside no cell (moved) and, of those, how many
  /// were outside every cell's padded bounding box (nearest cell by centroid).
  std::size_t moved = 0, far = 0;
};

/// Reference coordinates of x (3) in the cell with node coordinates
/// `nodes` (num_nodes x 3, row-major) of a mesh with coordinate element
/// `cmap`; false when the pull-back does not converge.
bool pull_back(const dolfinx::fem::CoordinateElement& cmap, std::span<const double> nodes,
               std::span<const double, 3> x, std::span<double, 3> X);

/// The point of the reference tetrahedron {X_i >= 0, X_0 + X_1 + X_2 <= 1}
/// nearest to X (Euclidean projection), in place; returns the distance moved.
double project_to_reference_tetrahedron(std::span<double, 3> X);

/// Cell of each point (row-major n x 3) among the local cells of `mesh`
/// (tetrahedra of any geometry order; the points are moved as described
/// in PointLocation). Local: no communication.
PointLocation locate_points(const dolfinx::mesh::Mesh& mesh, std::span<const double> points);
} // namespace breastsim
