// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A surface scan of the skin as read from a file: points (metres, scanner
// frame) and, for a triangulated scan, triangles by point index. A point
// cloud has no triangles. `where` names the file in every message.
#include <array>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <string>
#include <vector>

namespace breastsim::scan
{
using Vec3 = std::array<double, 3>;
using Triangle = std::array<std::int64_t, 3>;

/// The unit the user states for the scan's coordinates.
enum class Units
{
  mm,
  m
};

struct ScanSurface
{
  std::vector<Vec3> points;        ///< [m] after reading (scaled from the stated unit)
  std::vector<Triangle> triangles; ///< empty: a point cloud
  std::string where;               ///< "scan 'path'", for messages
  Units units = Units::mm;         ///< the unit stated for the file
  bool is_point_cloud() const { return triangles.empty(); }
};

inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 operator*(double s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

/// A point in the scan's stated unit, for messages: "(x, y, z) mm".
inline std::string point_text(const ScanSurface& s, const Vec3& p)
{
  const double k = s.units == Units::mm ? 1e3 : 1.0;
  return fmt::format("({:.6g}, {:.6g}, {:.6g}) {}", k * p[0], k * p[1], k * p[2], s.units == Units::mm ? "mm" : "m");
}
} // namespace breastsim::scan
