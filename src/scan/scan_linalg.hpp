// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The small dense linear algebra of the scan fit: the eigen-decomposition of
// a symmetric 3x3 matrix (Jacobi rotations) for plane fits, and a Cholesky
// solve of the normal equations of the surface fit.
#include "scan_surface.hpp"
#include <vector>

namespace breastsim::scan
{
struct Eigen3
{
  std::array<double, 3> values;  ///< ascending
  std::array<Vec3, 3> vectors;   ///< unit, vectors[k] for values[k]
};

/// Eigen-decomposition of the symmetric matrix a (row-major 3x3).
Eigen3 symmetric_eigen(std::array<double, 9> a);

/// Solve A x = b for symmetric positive definite A (n x n, row-major; A is
/// overwritten by its factor). Throws std::runtime_error when A is not
/// positive definite.
std::vector<double> cholesky_solve(std::vector<double> A, std::vector<double> b);

/// Least-squares plane through `points` with weights: its centroid and the
/// decomposition of the weighted covariance (normal = vectors[0]).
struct PlaneFit
{
  Vec3 centroid;
  Eigen3 spread;
};
PlaneFit fit_plane(const std::vector<Vec3>& points, const std::vector<double>& weights);
} // namespace breastsim::scan
