// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Distance from recorded points to a simulated (deformed) skin surface.
// Each point p is matched to its closest point q on the triangle surface;
// the residual is the normal distance
//     d(p) = (p - q) . n_t,
// n_t the unit outward normal of the closest triangle t: positive when the
// recording lies outside the simulated skin. For points whose closest point
// lies inside a triangle d is the signed Euclidean distance; on the rim of
// the half model (base, symmetry plane) the tangential offset is ignored, so
// that points recorded just beyond the model's edge are not penalised for it.
#include "recording.hpp"
#include "surface_export.hpp"
#include <vector>

namespace breastsim::calibration
{
struct SurfaceMatch
{
  double distance = 0;     ///< d(p) [m]
  Point closest{};         ///< q
  std::int32_t triangle = -1;
};

/// Closest point on triangle (a, b, c) to p (Ericson, Real-Time Collision
/// Detection, 5.1.5).
Point closest_point_on_triangle(const Point& p, const Point& a, const Point& b, const Point& c);

/// Match every point to the deformed surface of `s` (brute force over the
/// triangles with a bounding-sphere cut: fine for the ~1e3 triangles of a
/// diagnosis mesh).
std::vector<SurfaceMatch> match_points(const SkinSurface& s, const std::vector<Point>& points);

/// Derivatives of the distances of `matches` (match_points(s, points)) when
/// the vertices of s move with `velocity` (one per vertex), each point
/// keeping its triangle: with q in the plane of its triangle (a, b, c),
///   d = (p - a) . n,  n = m / |m|,  m = (b - a) x (c - a),
///   dd = -da . n + (p - a) . (I - n n^T) dm / |m|,
///   dm = (db - da) x (c - a) + (b - a) x (dc - da).
std::vector<double> distance_derivatives(const SkinSurface& s, const std::vector<Point>& points,
                                         const std::vector<SurfaceMatch>& matches,
                                         const std::vector<Point>& velocity);
} // namespace breastsim::calibration
