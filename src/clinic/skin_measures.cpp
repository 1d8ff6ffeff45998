// SPDX-License-Identifier: LGPL-3.0-or-later
#include "skin_measures.hpp"
#include "errors.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace breastsim::clinic
{
namespace
{
/// Boundary edges of the skin (edges of exactly one triangle), as a
/// neighbour list per vertex.
std::map<std::int32_t, std::vector<std::int32_t>> boundary_neighbours(const SkinSurface& s)
{
  std::map<std::pair<std::int32_t, std::int32_t>, int> count;
  for (const auto& t : s.triangles)
    for (int k = 0; k < 3; ++k)
    {
      const auto a = t[k], b = t[(k + 1) % 3];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  std::map<std::int32_t, std::vector<std::int32_t>> next;
  for (const auto& [e, n] : count)
    if (n == 1)
    {
      next[e.first].push_back(e.second);
      next[e.second].push_back(e.first);
    }
  return next;
}

/// Vertices from `start` along the boundary, first stepping to `first`,
/// while they lie in the symmetry plane (|x| of the reference at most
/// `plane_tolerance`): the last one is where the meridian meets the chest
/// (the base rim, or after surgery D, sewn to the chest).
std::vector<std::int32_t> walk_meridian(const SkinSurface& s,
                                        const std::map<std::int32_t, std::vector<std::int32_t>>& next,
                                        std::int32_t start, std::int32_t first, double plane_tolerance)
{
  std::vector<std::int32_t> path{start};
  std::int32_t prev = start, cur = first;
  for (std::size_t k = 0; k <= next.size() && std::abs(s.reference[cur][0]) <= plane_tolerance; ++k)
  {
    path.push_back(cur);
    const auto& n = next.at(cur);
    if (n.size() != 2)
      throw InputError("skin measures: the skin's boundary is not one loop (a vertex has "
                       + std::to_string(n.size()) + " boundary edges)");
    const std::int32_t step = n[0] == prev ? n[1] : n[0];
    prev = cur;
    cur = step;
  }
  if (path.size() < 2)
    throw InputError("skin measures: the skin's boundary leaves the symmetry plane at the nipple");
  return path;
}
} // namespace

Meridian skin_meridian(const SkinSurface& s, const Point& nipple, double plane_tolerance)
{
  if (!s.half_model)
    throw InputError("skin measures: clinical landmarks are measured on a half model (the cap)");
  const auto next = boundary_neighbours(s);
  std::int32_t start = -1;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [v, n] : next)
    if (const double d = distance(s.deformed[v], nipple); d < best && std::abs(s.reference[v][0]) <= plane_tolerance)
      best = d, start = v;
  if (start < 0 || next.at(start).size() != 2)
    throw InputError("skin measures: no skin boundary vertex near the nipple");
  auto a = walk_meridian(s, next, start, next.at(start)[0], plane_tolerance);
  auto b = walk_meridian(s, next, start, next.at(start)[1], plane_tolerance);
  // Order: the upper chest end first, the fold (the lower end) last.
  if (s.deformed[a.back()][2] < s.deformed[b.back()][2])
    std::swap(a, b);
  Meridian m;
  for (auto it = a.rbegin(); it != a.rend(); ++it)
    m.points.push_back(s.deformed[*it]);
  m.nipple = m.points.size() - 1;
  for (std::size_t k = 1; k < b.size(); ++k)
    m.points.push_back(s.deformed[b[k]]);
  return m;
}

double arc_length(const std::vector<Point>& p, std::size_t from)
{
  double L = 0;
  for (std::size_t k = from + 1; k < p.size(); ++k)
    L += distance(p[k - 1], p[k]);
  return L;
}

double nipple_to_fold(const SkinSurface& s, const Point& nipple, Point* fold, std::vector<Point>* path)
{
  const Meridian m = skin_meridian(s, nipple);
  if (fold)
    *fold = m.points.back();
  if (path)
  {
    *path = {nipple};
    path->insert(path->end(), m.points.begin() + static_cast<std::ptrdiff_t>(m.nipple + 1), m.points.end());
  }
  // From the nipple itself (it may lie between two meridian vertices after surgery).
  return distance(nipple, m.points[m.nipple + 1]) + arc_length(m.points, m.nipple + 1);
}

double skin_height(const SkinSurface& s, double x, double z)
{
  const double px = s.half_model ? std::abs(x) : x;
  double top = 0;
  for (const auto& t : s.triangles)
  {
    const Point &a = s.deformed[t[0]], &b = s.deformed[t[1]], &c = s.deformed[t[2]];
    // Barycentric coordinates of (px, z) in the triangle's projection onto the chest.
    const double det = (b[0] - a[0]) * (c[2] - a[2]) - (c[0] - a[0]) * (b[2] - a[2]);
    if (std::abs(det) < 1e-14)
      continue;
    const double l1 = ((px - a[0]) * (c[2] - a[2]) - (c[0] - a[0]) * (z - a[2])) / det;
    const double l2 = ((b[0] - a[0]) * (z - a[2]) - (px - a[0]) * (b[2] - a[2])) / det;
    if (l1 < -1e-12 || l2 < -1e-12 || l1 + l2 > 1 + 1e-12)
      continue;
    top = std::max(top, a[1] + l1 * (b[1] - a[1]) + l2 * (c[1] - a[1]));
  }
  return top;
}

double taut_tape(const SkinSurface& s, const Point& notch, const Point& nipple, double step, std::vector<Point>* path)
{
  // The profile (t, y) along the chest line from the notch to the nipple's
  // foot, ending at the nipple itself.
  const double dx = nipple[0] - notch[0], dz = nipple[2] - notch[2];
  const double L = std::hypot(dx, dz);
  const int n = std::max(2, static_cast<int>(std::ceil(L / step)));
  std::vector<std::array<double, 2>> profile;
  for (int k = 0; k < n; ++k)
  {
    const double f = static_cast<double>(k) / n;
    profile.push_back({f * L, skin_height(s, notch[0] + f * dx, notch[2] + f * dz)});
  }
  profile.push_back({L, nipple[1]});
  // Upper convex envelope (monotone chain): the line a taut tape takes.
  std::vector<std::array<double, 2>> hull;
  for (const auto& p : profile)
  {
    while (hull.size() >= 2)
    {
      const auto &o = hull[hull.size() - 2], &a = hull.back();
      if ((a[0] - o[0]) * (p[1] - o[1]) - (a[1] - o[1]) * (p[0] - o[0]) < 0)
        break; // a right turn keeps `a` on the upper envelope
      hull.pop_back();
    }
    hull.push_back(p);
  }
  double length = 0;
  for (std::size_t k = 1; k < hull.size(); ++k)
    length += std::hypot(hull[k][0] - hull[k - 1][0], hull[k][1] - hull[k - 1][1]);
  if (path) // (t, y) back to the chest frame: notch + t (dx, 0, dz) / L + y e_y
  {
    path->clear();
    for (const auto& [t, y] : hull)
      path->push_back({notch[0] + t * dx / L, y, notch[2] + t * dz / L});
  }
  return length;
}

double base_width(const SkinSurface& s, double chest_tolerance)
{
  double x = 0;
  for (std::size_t v = 0; v < s.reference.size(); ++v)
    if (s.reference[v][1] <= chest_tolerance)
      x = std::max(x, std::abs(s.deformed[v][0]));
  return 2 * x;
}

std::array<double, 3> closest_barycentric(const Point& p, const Point& a, const Point& b, const Point& c)
{
  auto sub = [](const Point& u, const Point& v) { return Point{u[0] - v[0], u[1] - v[1], u[2] - v[2]}; };
  auto dot = [](const Point& u, const Point& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  const Point ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0)
    return {1, 0, 0};
  const Point bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3)
    return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Point cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6)
    return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

double distance(const Point& a, const Point& b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

Point barycentric_point(const std::array<double, 3>& l, const Point& a, const Point& b, const Point& c)
{
  Point q{};
  for (int i = 0; i < 3; ++i)
    q[i] = l[0] * a[i] + l[1] * b[i] + l[2] * c[i];
  return q;
}

Point deformed_position(const SkinSurface& s, const Point& reference)
{
  double best = std::numeric_limits<double>::infinity();
  Point out{};
  for (const auto& t : s.triangles)
  {
    const auto l = closest_barycentric(reference, s.reference[t[0]], s.reference[t[1]], s.reference[t[2]]);
    const Point q = barycentric_point(l, s.reference[t[0]], s.reference[t[1]], s.reference[t[2]]);
    if (const double dist = distance(q, reference); dist < best)
      best = dist, out = barycentric_point(l, s.deformed[t[0]], s.deformed[t[1]], s.deformed[t[2]]);
  }
  return out;
}

SkinSurface skin_surface(const nlohmann::json& doc)
{
  SkinSurface s;
  const auto ref = doc.at("vertices_ref").get<std::vector<double>>();
  const auto def = doc.at("vertices").get<std::vector<double>>();
  const auto tri = doc.at("triangles").get<std::vector<std::int32_t>>();
  for (std::size_t k = 0; k + 2 < ref.size(); k += 3)
  {
    s.reference.push_back({ref[k], ref[k + 1], ref[k + 2]});
    s.deformed.push_back({def[k], def[k + 1], def[k + 2]});
  }
  for (std::size_t k = 0; k + 2 < tri.size(); k += 3)
    s.triangles.push_back({tri[k], tri[k + 1], tri[k + 2]});
  s.half_model = doc.at("mirror_x").get<bool>();
  return s;
}

int ptosis_grade(double nipple_below_fold)
{
  if (nipple_below_fold < -0.01)
    return 0;
  if (nipple_below_fold <= 0.01)
    return 1;
  return nipple_below_fold <= 0.03 ? 2 : 3;
}
} // namespace breastsim::clinic
