// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_checks.hpp"
#include "errors.hpp"
#include "scan_intersections.hpp"
#include "scan_topology.hpp"
#include <algorithm>
#include <cmath>
#include <tuple>
#include <unordered_map>

namespace breastsim::scan
{
namespace
{
double mm(double v) { return 1e3 * v; }

void check_points(const ScanSurface& s, const ScanLimits& l, bool chest)
{
  if (s.points.empty())
    throw InputError(s.where + ": empty: the file holds no points");
  for (std::size_t i = 0; i < s.points.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(s.points[i][k]))
        throw InputError(fmt::format("{}: vertex {} has a non-finite {} coordinate ({}): NaN or inf is no point",
                                     s.where, i, "xyz"[k], s.points[i][k]));
  const std::size_t need = chest ? 3 : l.min_points;
  if (s.points.size() < need)
    throw InputError(fmt::format("{}: too few points: {} (at least {} to fit a {})", s.where, s.points.size(), need,
                                 chest ? "chest plane" : "breast surface"));
}

/// The diagonal of the bounding box in metres must fit a breast.
void check_units(const ScanSurface& s, const ScanLimits& l, bool chest)
{
  Vec3 lo = s.points[0], hi = lo;
  for (const Vec3& p : s.points)
    for (int i = 0; i < 3; ++i)
    {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  const double d = norm(hi - lo);
  const double lo_ok = chest ? 0.2 * l.min_extent : l.min_extent, hi_ok = chest ? 3 * l.max_extent : l.max_extent;
  if (d < lo_ok || d > hi_ok)
  {
    const bool mm_units = s.units == Units::mm;
    throw InputError(fmt::format("{}: wrong units? the scan spans {:.4g} {} (bounding-box diagonal) in the stated unit "
                                 "--units {}, implausible for a {} ({:.0f} to {:.0f} mm){}",
                                 s.where, mm_units ? 1e3 * d : d, mm_units ? "mm" : "m", mm_units ? "mm" : "m",
                                 chest ? "chest wall" : "breast", mm(lo_ok), mm(hi_ok),
                                 d < lo_ok ? (mm_units ? "; is the file in metres (--units m)?" : "")
                                           : (mm_units ? "" : "; is the file in millimetres (--units mm)?")));
  }
}

/// A uniform hash grid of points for the nearest-point distance.
struct PointGrid
{
  double cell;
  std::unordered_map<std::uint64_t, std::vector<Vec3>> bins;
  static std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k)
  {
    return (static_cast<std::uint64_t>(i + (1 << 20)) << 42) ^ (static_cast<std::uint64_t>(j + (1 << 20)) << 21) ^
           static_cast<std::uint64_t>(k + (1 << 20));
  }
  std::int64_t idx(double v) const { return static_cast<std::int64_t>(std::floor(v / cell)); }
  void add(const Vec3& p) { bins[key(idx(p[0]), idx(p[1]), idx(p[2]))].push_back(p); }
  /// Distance to the nearest point, capped at `cell`.
  double nearest(const Vec3& p) const
  {
    double best = cell;
    for (auto i = idx(p[0]) - 1; i <= idx(p[0]) + 1; ++i)
      for (auto j = idx(p[1]) - 1; j <= idx(p[1]) + 1; ++j)
        for (auto k = idx(p[2]) - 1; k <= idx(p[2]) + 1; ++k)
          if (auto it = bins.find(key(i, j, k)); it != bins.end())
            for (const Vec3& q : it->second)
              best = std::min(best, norm(p - q));
    return best;
  }
};

/// Every point of the fitted surface within max_hole / 2 of a scan point.
void check_coverage(const ScanSurface& s, const BreastFrame& f, const RadialSurface& fit,
                    const std::vector<std::size_t>& used, const ScanLimits& l)
{
  PointGrid g{0.5 * l.max_hole, {}};
  for (std::size_t i : used)
    g.add(f.to_breast(s.points[i]));
  const int n = 48;
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b)
    {
      const double p = -1 + 2.0 * a / n, q = -1 + 2.0 * b / n;
      if (std::hypot(p, q) > 1)
        continue;
      const Vec3 x = fit.point(p, q);
      if (g.nearest(x) >= g.cell)
        throw InputError(fmt::format("{}: hole: the scan has no point within {:.1f} mm of the skin around {} (the "
                                     "fitted surface there); holes up to --max-hole = {:.1f} mm are bridged",
                                     s.where, mm(g.cell), point_text(s, f.to_scanner(x)), mm(l.max_hole)));
    }
}

/// The fitted surface is star-shaped about the origin with margin: r > 0
/// and its normal within 80 degrees of the radial direction.
void check_star_shape(const ScanSurface& s, const BreastFrame& f, const RadialSurface& fit)
{
  const int n = 48;
  const double h = 1e-4;
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b)
    {
      const double p = -1 + 2.0 * a / n, q = -1 + 2.0 * b / n;
      if (std::hypot(p, q) > 1 - h)
        continue;
      const Vec3 x = fit.point(p, q);
      const Vec3 normal = cross(fit.point(p + h, q) - fit.point(p - h, q), fit.point(p, q + h) - fit.point(p, q - h));
      const double c = std::abs(dot(normal, x)) / (norm(normal) * norm(x));
      if (!(fit.radius(p, q) > 0) || !(c > std::cos(80 * M_PI / 180)))
        throw InputError(fmt::format("{}: fold: the skin turns back on itself near {} (its normal is {:.0f} deg from the "
                                     "direction to the base centre): the breast must be star-shaped about the "
                                     "centre of its footprint",
                                     s.where, point_text(s, f.to_scanner(x)), std::acos(std::min(c, 1.0)) * 180 / M_PI));
    }
}
/// A triangulated skin faces away from the base centre: refused when more
/// than 2 % of its area faces it (cos < -0.2 between the outward normal and
/// the direction from the centre), an overhang or fold.
void check_overhang(const ScanSurface& s, const BreastFrame& f)
{
  double total = 0, facing = 0;
  std::size_t worst = 0, count = 0;
  double worst_cos = 1;
  const double sign = f.mirrored() ? -1 : 1; // a mirrored frame turns the triangles' orientation
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
  {
    const Vec3 a = f.to_breast(s.points[s.triangles[t][0]]), b = f.to_breast(s.points[s.triangles[t][1]]),
               c = f.to_breast(s.points[s.triangles[t][2]]);
    const Vec3 n = sign * cross(b - a, c - a), g = (1.0 / 3) * (a + b + c);
    const double area = 0.5 * norm(n), cosine = dot(n, g) / (norm(n) * norm(g));
    total += area;
    if (cosine < -0.2)
    {
      facing += area;
      ++count;
      if (cosine < worst_cos)
        std::tie(worst_cos, worst) = std::pair{cosine, t};
    }
  }
  if (facing > 0.02 * total)
    throw InputError(fmt::format("{}: fold: {} triangles ({:.1f} % of the skin's area) face the centre of the "
                                 "footprint, e.g. triangle {} at {} (an overhang); the breast must be star-shaped "
                                 "about the centre of its footprint",
                                 s.where, count, 100 * facing / total, worst,
                                 point_text(s, s.points[s.triangles[worst][0]])));
}
} // namespace

double robust_rms(std::vector<double> r)
{
  if (r.empty())
    return 0;
  for (double& v : r)
    v = std::abs(v);
  std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
  return 1.4826 * r[r.size() / 2];
}

void check_scan(const ScanSurface& s, const ScanLimits& l, bool chest)
{
  check_points(s, l, chest);
  check_units(s, l, chest);
  if (s.is_point_cloud())
    return;
  check_degenerate_triangles(s);
  check_duplicated_triangles(s);
  check_edges(s);
  check_connected(s);
  check_self_intersections(s);
}

std::vector<std::size_t> fit_points(const ScanSurface& s)
{
  std::vector<char> in(s.points.size(), s.is_point_cloud());
  for (const Triangle& t : s.triangles)
    for (auto v : t)
      in[v] = 1;
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < in.size(); ++i)
    if (in[i])
      used.push_back(i);
  return used;
}

void check_fit(const ScanSurface& s, const BreastFrame& f, const RadialSurface& fit,
               const std::vector<std::size_t>& used, const std::vector<double>& residuals, const ScanLimits& l)
{
  check_overhang(s, f);
  const double sigma = robust_rms(residuals);
  std::size_t worst = 0;
  for (std::size_t k = 1; k < residuals.size(); ++k)
    if (std::abs(residuals[k]) > std::abs(residuals[worst]))
      worst = k;
  if (std::abs(residuals[worst]) > std::max(l.max_spike, 8 * sigma))
    throw InputError(fmt::format("{}: spike: vertex {} at {} lies {:.1f} mm off the smooth skin through the other "
                                 "points (noise RMS {:.2f} mm; a point beyond --max-spike = {:.1f} mm and 8 noise RMS "
                                 "is a spike)",
                                 s.where, used[worst], point_text(s, s.points[used[worst]]), mm(residuals[worst]),
                                 mm(sigma), mm(l.max_spike)));
  if (sigma > l.max_noise)
    throw InputError(fmt::format("{}: noise: the points scatter {:.2f} mm (robust RMS) about the smooth skin, above "
                                 "--max-noise = {:.2f} mm (a rough or shaken scan, or a shape the fit cannot follow)",
                                 s.where, mm(sigma), mm(l.max_noise)));
  check_coverage(s, f, fit, used, l);
  check_star_shape(s, f, fit);
}
} // namespace breastsim::scan
