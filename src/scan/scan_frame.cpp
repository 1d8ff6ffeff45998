// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_frame.hpp"
#include "errors.hpp"
#include "scan_linalg.hpp"
#include "scan_topology.hpp"
#include <algorithm>
#include <cmath>

namespace breastsim::scan
{
namespace
{
Vec3 mean(const std::vector<Vec3>& points)
{
  Vec3 c{0, 0, 0};
  for (const Vec3& p : points)
    c = c + p;
  return (1.0 / points.size()) * c;
}

double mm(double v) { return 1e3 * v; }

/// Loops other than the footprint are holes: bridged by the fit when at
/// most `max_hole` across (the diagonal of their bounding box).
void check_holes(const ScanSurface& s, const std::vector<std::vector<std::int64_t>>& loops, std::size_t footprint,
                 double max_hole)
{
  for (std::size_t k = 0; k < loops.size(); ++k)
  {
    if (k == footprint)
      continue;
    Vec3 lo = s.points[loops[k][0]], hi = lo;
    for (auto v : loops[k])
      for (int i = 0; i < 3; ++i)
      {
        lo[i] = std::min(lo[i], s.points[v][i]);
        hi[i] = std::max(hi[i], s.points[v][i]);
      }
    if (norm(hi - lo) > max_hole)
      throw InputError(fmt::format("{}: hole: a boundary loop of {} edges around {} is {:.1f} mm across (vertex {} "
                                   "on it); holes up to --max-hole = {:.1f} mm are bridged by the fit",
                                   s.where, loops[k].size(), point_text(s, 0.5 * (lo + hi)), mm(norm(hi - lo)),
                                   loops[k][0], mm(max_hole)));
  }
}

/// The footprint loop (the longest open boundary), holes checked; empty when the skin has no boundary.
std::vector<std::int64_t> footprint_loop(const ScanSurface& s, bool have_chest, double max_hole)
{
  if (s.is_point_cloud())
  {
    if (!have_chest)
      throw InputError(s.where + ": a point cloud has no open boundary to find the chest wall from: give the chest "
                                 "wall as a second surface (--chest CHEST.stl) or a triangulated skin scan");
    return {};
  }
  const auto loops = boundary_loops(s);
  if (loops.empty())
  {
    if (!have_chest)
      throw InputError(s.where + ": footprint missing: the surface is closed (no open boundary); a breast scan is "
                                 "open where it meets the chest: cut it there or give the chest wall (--chest)");
    return {};
  }
  std::size_t best = 0;
  for (std::size_t k = 1; k < loops.size(); ++k)
    if (loop_length(s, loops[k]) > loop_length(s, loops[best]))
      best = k;
  check_holes(s, loops, best, max_hole);
  if (loops[best].size() < 8)
    throw InputError(fmt::format("{}: footprint degenerate: the open boundary has {} vertices (at least 8), at "
                                 "vertex {} {}",
                                 s.where, loops[best].size(), loops[best][0], point_text(s, s.points[loops[best][0]])));
  return loops[best];
}

/// The footprint's points, weighted by half their two edges (uniform along the curve).
PlaneFit footprint_plane(const ScanSurface& s, const std::vector<std::int64_t>& loop)
{
  std::vector<Vec3> pts;
  std::vector<double> w;
  for (std::size_t k = 0; k < loop.size(); ++k)
  {
    const Vec3& p = s.points[loop[k]];
    pts.push_back(p);
    w.push_back(0.5 * (norm(s.points[loop[(k + 1) % loop.size()]] - p) +
                       norm(s.points[loop[(k + loop.size() - 1) % loop.size()]] - p)));
  }
  const PlaneFit f = fit_plane(pts, w);
  if (f.spread.values[1] < 0.02 * f.spread.values[2])
    throw InputError(fmt::format("{}: footprint degenerate: the open boundary (from vertex {} {}) is nearly a line "
                                 "(spread {:.3g} mm across it, {:.3g} mm along it)",
                                 s.where, loop[0], point_text(s, s.points[loop[0]]), mm(std::sqrt(f.spread.values[1])),
                                 mm(std::sqrt(f.spread.values[2]))));
  return f;
}

/// Signed volume enclosed by the skin and the footprint's fan from `c`
/// (V = sum_t (a - c) . ((b - c) x (d - c)) / 6; the fan adds nothing):
/// positive when the triangles face away from the chest.
double enclosed_volume(const ScanSurface& s, const Vec3& c)
{
  double v = 0;
  for (const Triangle& t : s.triangles)
    v += dot(s.points[t[0]] - c, cross(s.points[t[1]] - c, s.points[t[2]] - c)) / 6;
  return v;
}

/// The breast in front of the chest: the chest surface's triangles (outward
/// normals by their order) or the skin's face away from the breast's side.
void check_side(const ScanSurface& skin, const ScanSurface* chest, const PlaneFit& plane, const Vec3& n)
{
  if (chest && !chest->is_point_cloud())
  {
    Vec3 m{0, 0, 0};
    for (const Triangle& t : chest->triangles)
      m = m + cross(chest->points[t[1]] - chest->points[t[0]], chest->points[t[2]] - chest->points[t[0]]);
    if (dot(m, n) < 0)
      throw InputError(fmt::format("{}: wrong side: the breast lies behind the chest wall {} (the chest's outward "
                                   "normals, by its triangles' order, point away from the breast); is the skin "
                                   "or the chest mirrored?",
                                   skin.where, chest->where));
  }
  else if (!skin.is_point_cloud() && enclosed_volume(skin, plane.centroid) < 0)
    throw InputError(fmt::format("{}: wrong side: the skin's outward normals (by its triangles' order) point toward "
                                 "the chest wall: the breast is on the wrong side of its footprint, or the "
                                 "surface is inside out (reverse its triangles)",
                                 skin.where));
}

/// Unit vector along `v` with its components along `a` (and `b`) removed;
/// InputError naming `option` when little is left.
Vec3 orthogonal_axis(Vec3 v, const Vec3& a, const Vec3* b, const std::string& option)
{
  const double len = norm(v);
  v = v - dot(v, a) * a;
  if (b)
    v = v - dot(v, *b) * *b;
  if (!(norm(v) > 0.3 * len))
    throw InputError(fmt::format("{} ({:.3g}, {:.3g}, {:.3g}) is nearly along the chest normal{} ({:.3g}, {:.3g}, "
                                 "{:.3g}) found in the scan; give the scanner's direction of it",
                                 option, v[0], v[1], v[2], b ? " or --up" : "", a[0], a[1], a[2]));
  return (1 / norm(v)) * v;
}

/// The nipple: the landmark (within 10 mm of a skin point), else the mean
/// of the skin points within 2 mm of the most anterior one.
Vec3 find_nipple(const ScanSurface& s, const Vec3& o, const Vec3& n, const FrameOptions& opt)
{
  if (opt.nipple)
  {
    double best = 1e300;
    for (const Vec3& p : s.points)
      best = std::min(best, norm(p - *opt.nipple));
    if (best > 0.01)
      throw InputError(fmt::format("{}: --nipple {} is {:.1f} mm from the nearest point of the scan (at most 10 mm)",
                                   s.where, point_text(s, *opt.nipple), mm(best)));
    return *opt.nipple;
  }
  double top = -1e300;
  for (const Vec3& p : s.points)
    top = std::max(top, dot(p - o, n));
  Vec3 c{0, 0, 0};
  int count = 0;
  for (const Vec3& p : s.points)
    if (dot(p - o, n) >= top - 0.002)
    {
      c = c + p;
      ++count;
    }
  return (1.0 / count) * c;
}
} // namespace

BreastFrame breast_frame(const ScanSurface& skin, const ScanSurface* chest, const FrameOptions& o, double max_hole)
{
  BreastFrame f;
  f.footprint = footprint_loop(skin, chest != nullptr, max_hole);
  const PlaneFit plane = chest ? fit_plane(chest->points, std::vector<double>(chest->points.size(), 1.0))
                               : footprint_plane(skin, f.footprint);
  Vec3 n = plane.spread.vectors[0];
  const Vec3 skin_centroid = mean(skin.points);
  if (dot(skin_centroid - plane.centroid, n) < 0)
    n = -1.0 * n;
  check_side(skin, chest, plane, n);
  std::vector<Vec3> rim;
  for (auto v : f.footprint)
    rim.push_back(skin.points[v]);
  if (rim.empty()) // a point cloud (or closed skin) over a chest: the skin near the chest plane
    for (const Vec3& p : skin.points)
      if (dot(p - plane.centroid, n) < 0.005)
        rim.push_back(p);
  if (rim.size() < 8)
    throw InputError(fmt::format("{}: footprint missing: {} skin points lie within 5 mm of the chest wall {} (at least "
                                 "8): the scan does not reach the chest",
                                 skin.where, rim.size(), chest ? chest->where : "plane"));
  Vec3 c = mean(rim);
  c = c - dot(c - plane.centroid, n) * n; // onto the chest plane
  for (const Vec3& p : rim)
  {
    f.footprint_off_plane = std::max(f.footprint_off_plane, std::abs(dot(p - c, n)));
    f.footprint_radius += norm((p - c) - dot(p - c, n) * n) / rim.size();
  }
  if (f.footprint_off_plane > 0.3 * f.footprint_radius)
    throw InputError(fmt::format("{}: footprint not planar: its points lie up to {:.1f} mm off the fitted chest "
                                 "plane (mean footprint radius {:.1f} mm); give the chest wall as a surface (--chest)",
                                 skin.where, mm(f.footprint_off_plane), mm(f.footprint_radius)));
  f.ey = n;
  f.ez = orthogonal_axis(o.up, n, nullptr, "--up");
  f.ex = orthogonal_axis(o.lateral, n, &f.ez, "--lateral");
  f.nipple = find_nipple(skin, c, n, o);
  f.origin = c + dot(f.nipple - c, f.ex) * f.ex;
  return f;
}
} // namespace breastsim::scan
