// SPDX-License-Identifier: LGPL-3.0-or-later
#include "surface_distance.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace breastsim::calibration
{
namespace
{
Point sub(const Point& a, const Point& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point add_scaled(const Point& a, double s, const Point& d)
{
  return {a[0] + s * d[0], a[1] + s * d[1], a[2] + s * d[2]};
}
Point cross(const Point& a, const Point& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
} // namespace

TrianglePoint closest_on_triangle(const Point& p, const Point& a, const Point& b, const Point& c)
{
  const Point ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0)
    return {a, {1, 0, 0}}; // vertex region A
  const Point bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3)
    return {b, {0, 1, 0}}; // vertex region B
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    const double t = d1 / (d1 - d3);
    return {add_scaled(a, t, ab), {1 - t, t, 0}}; // edge AB
  }
  const Point cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6)
    return {c, {0, 0, 1}}; // vertex region C
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    const double t = d2 / (d2 - d6);
    return {add_scaled(a, t, ac), {1 - t, 0, t}}; // edge AC
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {add_scaled(b, t, sub(c, b)), {0, 1 - t, t}}; // edge BC
  }
  const double den = 1 / (va + vb + vc); // interior: barycentric (u, v, w)
  const double v = vb * den, w = vc * den;
  return {add_scaled(add_scaled(a, v, ab), w, ac), {1 - v - w, v, w}};
}

Point closest_point_on_triangle(const Point& p, const Point& a, const Point& b, const Point& c)
{
  return closest_on_triangle(p, a, b, c).q;
}

namespace
{
/// The rim of a triangle surface: its edges used by one triangle only, and
/// the vertices on them.
struct Rim
{
  std::set<std::pair<std::int32_t, std::int32_t>> edges;
  std::vector<bool> vertices;

  explicit Rim(const SkinSurface& s) : vertices(s.deformed.size(), false)
  {
    std::map<std::pair<std::int32_t, std::int32_t>, int> uses;
    for (const auto& t : s.triangles)
      for (int k = 0; k < 3; ++k)
        ++uses[edge(t[k], t[(k + 1) % 3])];
    for (const auto& [e, n] : uses)
      if (n == 1)
      {
        edges.insert(e);
        vertices[e.first] = vertices[e.second] = true;
      }
  }
  static std::pair<std::int32_t, std::int32_t> edge(std::int32_t i, std::int32_t j)
  {
    return {std::min(i, j), std::max(i, j)};
  }
  /// True if the closest point with barycentric weights w on triangle t
  /// lies on a vertex or an edge shared by several triangles.
  bool on_inner_feature(const std::array<std::int32_t, 3>& t, const std::array<double, 3>& w) const
  {
    std::vector<std::int32_t> support;
    for (int k = 0; k < 3; ++k)
      if (w[k] != 0)
        support.push_back(t[k]);
    if (support.size() == 1)
      return !vertices[support[0]];
    if (support.size() == 2)
      return edges.count(edge(support[0], support[1])) == 0;
    return false; // inside the triangle
  }
};
} // namespace

std::vector<SurfaceMatch> match_points(const SkinSurface& s, const std::vector<Point>& points)
{
  // Bounding sphere of each triangle (centroid, radius) to skip far ones.
  const std::size_t nt = s.triangles.size();
  std::vector<Point> centre(nt), normal(nt);
  std::vector<double> radius(nt);
  for (std::size_t t = 0; t < nt; ++t)
  {
    const auto& tri = s.triangles[t];
    const Point &a = s.deformed[tri[0]], &b = s.deformed[tri[1]], &c = s.deformed[tri[2]];
    for (int k = 0; k < 3; ++k)
      centre[t][k] = (a[k] + b[k] + c[k]) / 3;
    radius[t] = std::sqrt(std::max({dot(sub(a, centre[t]), sub(a, centre[t])),
                                    dot(sub(b, centre[t]), sub(b, centre[t])),
                                    dot(sub(c, centre[t]), sub(c, centre[t]))}));
    Point n = cross(sub(b, a), sub(c, a)); // triangles are counter-clockwise seen from outside
    const double len = std::sqrt(dot(n, n));
    normal[t] = {n[0] / len, n[1] / len, n[2] / len};
  }
  const Rim rim(s);
  std::vector<SurfaceMatch> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const Point& p = points[i];
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < nt; ++t)
    {
      const Point d = sub(p, centre[t]);
      const double lower = std::sqrt(dot(d, d)) - radius[t]; // no point of t is closer
      if (lower > 0 && lower * lower >= best)
        continue;
      const auto& tri = s.triangles[t];
      const TrianglePoint q = closest_on_triangle(p, s.deformed[tri[0]], s.deformed[tri[1]],
                                                  s.deformed[tri[2]]);
      const Point pq = sub(p, q.q);
      const double d2 = dot(pq, pq);
      if (d2 < best)
      {
        best = d2;
        out[i].closest = q.q;
        out[i].weights = q.w;
        out[i].triangle = static_cast<std::int32_t>(t);
      }
    }
    SurfaceMatch& m = out[i];
    const Point pq = sub(p, m.closest);
    const double normal_part = dot(pq, normal[m.triangle]);
    // On a vertex or edge inside the surface: |p - q|, signed by n_t (the
    // same for every triangle sharing q); inside a triangle and on the rim:
    // the normal part.
    m.to_point = rim.on_inner_feature(s.triangles[m.triangle], m.weights) && best > 0;
    m.distance = m.to_point ? std::copysign(std::sqrt(best), normal_part) : normal_part;
  }
  return out;
}
} // namespace breastsim::calibration

namespace breastsim::calibration
{
std::vector<double> distance_derivatives(const SkinSurface& s, const std::vector<Point>& points,
                                         const std::vector<SurfaceMatch>& matches,
                                         const std::vector<Point>& velocity)
{
  std::vector<double> out(points.size(), 0.0);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const SurfaceMatch& match = matches[i];
    const auto& tri = s.triangles[match.triangle];
    const Point &a = s.deformed[tri[0]], &b = s.deformed[tri[1]], &c = s.deformed[tri[2]];
    const Point &da = velocity[tri[0]], &db = velocity[tri[1]], &dc = velocity[tri[2]];
    if (match.to_point) // d = e . (p - q), e = (p - q) / d  =>  dd = -e . dq
    {
      const Point e = sub(points[i], match.closest);
      const auto& w = match.weights;
      double dd = 0;
      for (int k = 0; k < 3; ++k)
        dd -= e[k] / match.distance * (w[0] * da[k] + w[1] * db[k] + w[2] * dc[k]);
      out[i] = dd;
      continue;
    }
    const Point m = cross(sub(b, a), sub(c, a));
    const double len = std::sqrt(dot(m, m));
    const Point n = {m[0] / len, m[1] / len, m[2] / len};
    // dm = (db - da) x (c - a) + (b - a) x (dc - da);  dn = (I - n n^T) dm / |m|
    const Point dm1 = cross(sub(db, da), sub(c, a)), dm2 = cross(sub(b, a), sub(dc, da));
    const Point dm = {dm1[0] + dm2[0], dm1[1] + dm2[1], dm1[2] + dm2[2]};
    const double ndm = dot(n, dm);
    const Point dn = {(dm[0] - ndm * n[0]) / len, (dm[1] - ndm * n[1]) / len,
                      (dm[2] - ndm * n[2]) / len};
    // d = (p - a) . n  =>  dd = -da . n + (p - a) . dn
    out[i] = -dot(da, n) + dot(sub(points[i], a), dn);
  }
  return out;
}
} // namespace breastsim::calibration
