// SPDX-License-Identifier: LGPL-3.0-or-later
#include "surface_distance.hpp"
#include <cmath>
#include <limits>

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

Point closest_point_on_triangle(const Point& p, const Point& a, const Point& b, const Point& c)
{
  const Point ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0)
    return a; // vertex region A
  const Point bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3)
    return b; // vertex region B
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
    return add_scaled(a, d1 / (d1 - d3), ab); // edge AB
  const Point cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6)
    return c; // vertex region C
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
    return add_scaled(a, d2 / (d2 - d6), ac); // edge AC
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return add_scaled(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), sub(c, b)); // edge BC
  const double den = 1 / (va + vb + vc); // interior: barycentric (u, v, w)
  const double v = vb * den, w = vc * den;
  return add_scaled(add_scaled(a, v, ab), w, ac);
}

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
      const Point q = closest_point_on_triangle(p, s.deformed[tri[0]], s.deformed[tri[1]],
                                                s.deformed[tri[2]]);
      const Point pq = sub(p, q);
      const double d2 = dot(pq, pq);
      if (d2 < best)
      {
        best = d2;
        out[i].closest = q;
        out[i].triangle = static_cast<std::int32_t>(t);
      }
    }
    out[i].distance = dot(sub(p, out[i].closest), normal[out[i].triangle]);
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
    const auto& tri = s.triangles[matches[i].triangle];
    const Point &a = s.deformed[tri[0]], &b = s.deformed[tri[1]], &c = s.deformed[tri[2]];
    const Point &da = velocity[tri[0]], &db = velocity[tri[1]], &dc = velocity[tri[2]];
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
