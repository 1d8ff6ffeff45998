// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Distance from recorded points to a simulated (deformed) skin surface.
// Each point p is matched to its closest point q on the triangle surface,
// n_t the unit outward normal of the closest triangle t. The residual is
// the signed Euclidean distance
//     d(p) = sign((p - q) . n_t) |p - q|,
// positive when the recording lies outside the simulated skin. It is
// continuous where the closest triangle changes (q on an edge or vertex
// shared by several triangles gives the same d from each), so it does not
// depend on the order of the triangles (nor on the MPI partition). On the
// rim of the half model (base, symmetry plane) only the normal part
//     d(p) = (p - q) . n_t
// counts, so that points recorded just beyond the model's edge are not
// penalised for their tangential offset.
#include "recording.hpp"
#include "surface_export.hpp"
#include <array>
#include <vector>

namespace breastsim::calibration
{
struct SurfaceMatch
{
  double distance = 0;     ///< d(p) [m]
  Point closest{};         ///< q
  std::array<double, 3> weights{}; ///< q's barycentric coordinates on its triangle
  bool to_point = false;   ///< d = sign |p - q| (q on an inner edge or vertex), else (p - q) . n_t
  std::int32_t triangle = -1;
};

/// A point on a triangle (a, b, c): q = w_0 a + w_1 b + w_2 c.
struct TrianglePoint
{
  Point q;
  std::array<double, 3> w;
};

/// Closest point on triangle (a, b, c) to p with its barycentric
/// coordinates, exactly 0 off its vertex or edge region (Ericson,
/// Real-Time Collision Detection, 5.1.5).
TrianglePoint closest_on_triangle(const Point& p, const Point& a, const Point& b, const Point& c);
/// Its point q only.
Point closest_point_on_triangle(const Point& p, const Point& a, const Point& b, const Point& c);

/// Match every point to the deformed surface of `s` (brute force over the
/// triangles with a bounding-sphere cut: fine for the ~1e3 triangles of a
/// diagnosis mesh).
std::vector<SurfaceMatch> match_points(const SkinSurface& s, const std::vector<Point>& points);

/// Derivatives of the distances of `matches` (match_points(s, points)) when
/// the vertices of s move with `velocity` (one per vertex), each point
/// keeping its triangle (a, b, c). For d = sign |p - q| (to_point), q's
/// barycentric coordinates w held (the envelope theorem):
///   dd = -e . (w_0 da + w_1 db + w_2 dc),  e = (p - q) / d;
/// for the normal part, with q in the plane of the triangle,
///   d = (p - a) . n,  n = m / |m|,  m = (b - a) x (c - a),
///   dd = -da . n + (p - a) . (I - n n^T) dm / |m|,
///   dm = (db - da) x (c - a) + (b - a) x (dc - da).
std::vector<double> distance_derivatives(const SkinSurface& s, const std::vector<Point>& points,
                                         const std::vector<SurfaceMatch>& matches,
                                         const std::vector<Point>& velocity);
} // namespace breastsim::calibration
