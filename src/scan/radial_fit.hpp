// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The skin as a star-shaped surface about the base centre (the origin of the
// breast frame, on the chest plane y = 0): x = r(d) d for unit directions d
// with d_y >= 0. A direction is written in disk coordinates by the
// azimuthal equidistant map of the half sphere onto the unit disk,
//   alpha = acos(d_y), beta = atan2(d_z, d_x),
//   (p, q) = (2 alpha / pi) (cos beta, sin beta),
// so that the chest plane is the circle p^2 + q^2 = 1 and the chest normal
// the centre. r is a sum of Chebyshev products up to total degree N,
//   r(p, q) = sum_{i + j <= N} c_ij T_i(p) T_j(q),
// fitted to the scan's points by least squares with a smoothing penalty
// lambda sum (i + j)^4 c_ij^2 (holes are bridged by the smooth surface).
#include "scan_surface.hpp"
#include <vector>

namespace breastsim::scan
{
std::array<double, 2> disk_coords(const Vec3& d);
/// The unit direction of disk point (p, q).
Vec3 disk_direction(double p, double q);

struct RadialSurface
{
  int degree = 0;
  std::vector<double> coef; ///< c_ij in the order i = 0..N, j = 0..N - i
  double radius(double p, double q) const;
  double radius(const Vec3& d) const; ///< d unit
  Vec3 point(double p, double q) const { return radius(p, q) * disk_direction(p, q); }
};

/// Fit r to `points` (breast frame, none at the origin). `smoothing` is
/// lambda relative to the mean diagonal of the normal equations.
RadialSurface fit_radial(const std::vector<Vec3>& points, int degree, double smoothing);

/// Volume under the surface: V = int r^3 / 3 dOmega over the half sphere.
double radial_volume(const RadialSurface& f);

/// |x| - r(x / |x|) of each point: the radial distance to the surface.
std::vector<double> radial_residuals(const RadialSurface& f, const std::vector<Vec3>& points);
} // namespace breastsim::scan
