// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_intersections.hpp"
#include "errors.hpp"
#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

namespace breastsim::scan
{
namespace
{
/// Where the segment p q crosses the interior of triangle a b c (Moeller and
/// Trumbore 1997): p + t (q - p) = a + u (b - a) + v (c - a) with t, u, v,
/// 1 - u - v all in (eps, 1 - eps); none when parallel.
std::optional<Vec3> segment_crossing(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c)
{
  constexpr double eps = 1e-9;
  const Vec3 d = q - p, e1 = b - a, e2 = c - a;
  const Vec3 h = cross(d, e2);
  const double det = dot(e1, h);
  if (std::abs(det) <= 1e-14 * norm(d) * norm(e1) * norm(e2))
    return std::nullopt;
  const Vec3 sv = p - a;
  const double u = dot(sv, h) / det;
  const Vec3 qv = cross(sv, e1);
  const double v = dot(d, qv) / det, t = dot(e2, qv) / det;
  if (u > eps && v > eps && u + v < 1 - eps && t > eps && t < 1 - eps)
    return p + t * d;
  return std::nullopt;
}

std::optional<Vec3> triangles_cross(const ScanSurface& s, const Triangle& A, const Triangle& B)
{
  for (int pass = 0; pass < 2; ++pass)
  {
    const Triangle& E = pass == 0 ? A : B;
    const Triangle& T = pass == 0 ? B : A;
    for (int k = 0; k < 3; ++k)
      if (auto x = segment_crossing(s.points[E[k]], s.points[E[(k + 1) % 3]], s.points[T[0]], s.points[T[1]],
                                    s.points[T[2]]))
        return x;
  }
  return std::nullopt;
}

bool share_vertex(const Triangle& a, const Triangle& b)
{
  for (auto i : a)
    for (auto j : b)
      if (i == j)
        return true;
  return false;
}

struct Grid
{
  Vec3 lo;
  double cell;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> bins;
  std::array<std::int64_t, 3> index(const Vec3& p) const
  {
    return {static_cast<std::int64_t>(std::floor((p[0] - lo[0]) / cell)),
            static_cast<std::int64_t>(std::floor((p[1] - lo[1]) / cell)),
            static_cast<std::int64_t>(std::floor((p[2] - lo[2]) / cell))};
  }
  static std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k)
  {
    return (static_cast<std::uint64_t>(i) << 42) ^ (static_cast<std::uint64_t>(j) << 21) ^ static_cast<std::uint64_t>(k);
  }
};

/// Each triangle into the grid cells its bounding box touches (cell: twice
/// the mean edge length).
Grid bin_triangles(const ScanSurface& s)
{
  Grid g{s.points[0], 0, {}};
  double edges = 0;
  for (const Vec3& p : s.points)
    for (int i = 0; i < 3; ++i)
      g.lo[i] = std::min(g.lo[i], p[i]);
  for (const Triangle& t : s.triangles)
    edges += norm(s.points[t[1]] - s.points[t[0]]);
  g.cell = std::max(2 * edges / s.triangles.size(), 1e-12);
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
  {
    Vec3 lo = s.points[s.triangles[t][0]], hi = lo;
    for (int k = 1; k < 3; ++k)
      for (int i = 0; i < 3; ++i)
      {
        lo[i] = std::min(lo[i], s.points[s.triangles[t][k]][i]);
        hi[i] = std::max(hi[i], s.points[s.triangles[t][k]][i]);
      }
    const auto a = g.index(lo), b = g.index(hi);
    for (auto i = a[0]; i <= b[0]; ++i)
      for (auto j = a[1]; j <= b[1]; ++j)
        for (auto k = a[2]; k <= b[2]; ++k)
          g.bins[Grid::key(i, j, k)].push_back(t);
  }
  return g;
}
} // namespace

void check_self_intersections(const ScanSurface& s)
{
  if (s.triangles.empty())
    return;
  const Grid g = bin_triangles(s);
  std::vector<std::uint64_t> keys;
  for (const auto& [k, v] : g.bins)
    keys.push_back(k);
  std::sort(keys.begin(), keys.end()); // report the same pair on every run
  for (std::uint64_t key : keys)
  {
    const auto& tris = g.bins.at(key);
    for (std::size_t i = 0; i < tris.size(); ++i)
      for (std::size_t j = i + 1; j < tris.size(); ++j)
      {
        const Triangle &A = s.triangles[tris[i]], &B = s.triangles[tris[j]];
        if (share_vertex(A, B))
          continue;
        if (auto x = triangles_cross(s, A, B))
          throw InputError(fmt::format("{}: self-intersecting triangles {} and {} cross at {}; the skin surface must "
                                       "not pass through itself",
                                       s.where, std::min(tris[i], tris[j]), std::max(tris[i], tris[j]),
                                       point_text(s, *x)));
      }
  }
}
} // namespace breastsim::scan
