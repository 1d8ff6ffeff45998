// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Mesh morphing of the neutral half cap (docs/MODEL.md): move the nodes of a mesh
// of the cap (R0, H0) onto the cap (R, H) without changing the topology, so
// that the observables are smooth functions of R and H (a calibration can
// difference them with small steps; remeshing makes them jump).
//
// The map is radial from the base centre O = (0, 0, 0). The cap is
// star-shaped about O: the ray p = s d (|d| = 1, d_y >= 0) leaves the sphere
// of radius Rs = (R^2 + H^2) / (2H), centre (0, yc, 0), yc = H - Rs, at
//   t(d_y) = d_y yc + sqrt(d_y^2 yc^2 + R^2)     (using Rs^2 - yc^2 = R^2),
// so each node moves along its ray by the ratio of the two exit distances:
//   p' = p * t(d_y; R, H) / t(d_y; R0, H0),   d_y = p_y / |p|.
// Skin nodes (|p| = t0) land on the new sphere, the base y = 0 stays in
// y = 0 (scaled by R/R0), the symmetry plane x = 0 stays x = 0, the apex
// (0, H0, 0) goes to (0, H, 0). The node positions are analytic in R, H.
#include <span>

namespace breastsim::meshes
{
struct CapShape
{
  double R = 0.07; ///< base radius [m]
  double H = 0.06; ///< height [m]
};

/// Distance from the base centre to the cap's skin along a unit direction
/// with y-component `dy` in [0, 1]: t = dy yc + sqrt(dy^2 yc^2 + R^2).
double cap_exit_distance(const CapShape& cap, double dy);

/// Map `x` (points, row-major (n, 3)) of the cap `from` onto the cap `to`,
/// in place. Throws std::invalid_argument for R or H <= 0.
void morph_cap(std::span<double> x, const CapShape& from, const CapShape& to);
} // namespace breastsim::meshes
