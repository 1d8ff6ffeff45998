// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_landmarks.hpp"
#include "errors.hpp"
#include "scan_model.hpp"
#include "scan_readers.hpp"
#include "skin_measures.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>

namespace breastsim::clinic
{
using scan::operator*;

namespace
{
/// Join ring `a` to the next ring `b` outward on the disk of directions by
/// walking both in angle; triangles counter-clockwise seen from outside.
void zip_rings(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b,
               std::vector<std::array<std::int32_t, 3>>& tri)
{
  const std::size_t na = a.size(), nb = b.size();
  std::size_t ia = 0, ib = 0;
  while (ib < nb || (na > 1 && ia < na))
  {
    const double next_a = na > 1 && ia < na ? (ia + 1.0) / na : 2.0, next_b = ib < nb ? (ib + 1.0) / nb : 2.0;
    if (next_b <= next_a)
      tri.push_back({a[ia % na], b[(ib + 1) % nb], b[ib]}), ++ib;
    else
      tri.push_back({a[ia], a[(ia + 1) % na], b[ib % nb]}), ++ia;
  }
}

/// The fitted skin on rings of the disk of directions: ring i of `rings`
/// at radius i / rings with 6 i points (about even spacing on the disk).
SkinSurface triangulate(const scan::RadialSurface& f, int rings = 32)
{
  SkinSurface s;
  s.half_model = false;
  std::vector<std::int32_t> inner;
  for (int i = 0; i <= rings; ++i)
  {
    const int m = i == 0 ? 1 : 6 * i;
    std::vector<std::int32_t> ring;
    for (int j = 0; j < m; ++j)
    {
      const double rho = static_cast<double>(i) / rings, t = 2 * std::numbers::pi * j / m;
      ring.push_back(static_cast<std::int32_t>(s.deformed.size()));
      s.deformed.push_back(f.point(rho * std::cos(t), rho * std::sin(t)));
    }
    if (i > 0)
      zip_rings(inner, ring, s.triangles);
    inner = std::move(ring);
  }
  s.reference = s.deformed;
  return s;
}

/// Refuse a value measured on the scan outside the landmark's accepted range.
void check_measured(const std::string& key, double value, const std::filesystem::path& file)
{
  if (const LandmarkRange* r = violated_range(key, value))
    throw InputError(fmt::format("scan '{}': {} measured on it = {:.1f} cm is out of range: [{:.0f}, {:.0f}] cm "
                                 "({}); check the scan's frame (up, lateral, nipple)",
                                 file.string(), key, 100 * value, 100 * r->lo, 100 * r->hi, r->why));
}
} // namespace

ScannedSkin read_scanned_skin(const SideScan& in)
{
  scan::ScanModelOptions o;
  o.units = in.units;
  o.frame.up = in.up;
  o.frame.lateral = in.lateral;
  o.frame.nipple = in.nipple;
  const scan::ScanSurface surface = scan::read_scan(in.file, in.units);
  const scan::ScanModel m = scan::fit_scan(surface, nullptr, o);
  ScannedSkin s;
  s.frame = m.frame;
  s.fit = m.fit;
  s.skin = triangulate(m.fit);
  s.volume = scan::radial_volume(m.fit);
  s.noise_rms = m.noise_rms;
  s.points = m.points;
  // The nipple on the fitted skin, in the sagittal plane x = 0 (as scan-model places it).
  const Point n = m.frame.to_breast(m.frame.nipple);
  Point d{0, n[1], n[2]};
  d = (1 / scan::norm(d)) * d;
  s.nipple = m.fit.radius(d) * d;
  return s;
}

ScanMeasures measure_scan(const ScannedSkin& s, const std::optional<Point>& notch_scanner)
{
  ScanMeasures out;
  // N-IMF: the meridian p = 0 of the disk (the plane x = 0) from the nipple to q = -1 (the chest).
  const double q0 = scan::disk_coords((1 / scan::norm(s.nipple)) * s.nipple)[1];
  const int n = 400;
  out.n_imf_path = {s.nipple};
  for (int k = 1; k <= n; ++k)
    out.n_imf_path.push_back(s.fit.point(0.0, q0 + (-1.0 - q0) * k / n));
  out.fold = out.n_imf_path.back();
  auto& l = out.landmarks;
  l.n_imf = arc_length(out.n_imf_path, 0);
  double xmin = 0, xmax = 0, ymax = 0;
  for (const auto& p : s.skin.deformed)
  {
    ymax = std::max(ymax, p[1]);
    if (p[1] < 1e-9) // the footprint ring lies on the chest plane
      xmin = std::min(xmin, p[0]), xmax = std::max(xmax, p[0]);
  }
  l.base_width = xmax - xmin;
  l.projection = ymax;
  l.ptosis_grade = ptosis_grade(out.fold[2] - s.nipple[2]);
  if (notch_scanner)
  {
    const Point b = s.frame.to_breast(*notch_scanner);
    if (std::abs(b[1]) > 0.03 || b[0] >= s.nipple[0])
      throw InputError(fmt::format("scan: the notch lies {:.0f} mm {} of the nipple and {:.0f} mm off the chest "
                                   "plane: it must lie medial of the nipple (x < 0) within 30 mm of the plane; "
                                   "check its coordinates and the scan's 'lateral' direction",
                                   1e3 * std::abs(b[0]), b[0] >= 0 ? "lateral" : "medial", 1e3 * std::abs(b[1])));
    out.notch = Point{b[0], 0.0, b[2]};
    l.sn_n = taut_tape(s.skin, *out.notch, s.nipple);
    l.nipple_midline = s.nipple[0] - b[0];
  }
  return out;
}

SideLandmarks scan_landmarks(const ScanMeasures& m, const SideLandmarks& entered, const std::filesystem::path& file)
{
  SideLandmarks l = m.landmarks;
  if (!m.notch)
    l.sn_n = entered.sn_n, l.nipple_midline = entered.nipple_midline;
  for (const auto& [key, v] : {std::pair{"sn_n", l.sn_n}, {"n_imf", l.n_imf}, {"base_width", l.base_width},
                               {"nipple_midline", l.nipple_midline}, {"projection", *l.projection}})
    check_measured(key, v, file);
  if (l.nipple_midline < l.base_width / 2)
    throw InputError(fmt::format("scan '{}': the nipple lies {:.1f} cm from the midline, less than half the "
                                 "scan's base width ({:.1f} cm): the base would cross the midline",
                                 file.string(), 100 * l.nipple_midline, 50 * l.base_width));
  return l;
}

double volume_under(const SkinSurface& s)
{
  double v = 0;
  for (const auto& t : s.triangles)
  {
    const Point &a = s.deformed[t[0]], &b = s.deformed[t[1]], &c = s.deformed[t[2]];
    // (n A)_y = ((b - a) x (c - a))_y / 2
    const double ny_area = 0.5 * ((b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]));
    v += ny_area * (a[1] + b[1] + c[1]) / 3;
  }
  return s.half_model ? 2 * v : v;
}

ScanComparison compare_with_scan(const ScannedSkin& s, const Point& scan_fold, const SkinSurface& model,
                                 const Point& model_fold)
{
  ScanComparison c;
  c.shift = {scan_fold[0] - model_fold[0], 0.0, scan_fold[2] - model_fold[2]};
  // The model's skin in the scan's frame, mirrored when it is a half model.
  std::vector<std::array<Point, 3>> tri;
  for (const auto& t : model.triangles)
    for (double sx : model.half_model ? std::vector<double>{1, -1} : std::vector<double>{1})
    {
      std::array<Point, 3> p;
      for (int k = 0; k < 3; ++k)
      {
        const Point& q = model.deformed[t[k]];
        p[k] = {sx * q[0] + c.shift[0], q[1] + c.shift[1], q[2] + c.shift[2]};
      }
      tri.push_back(p);
    }
  // Each scan vertex's distance, weighted by a third of its triangles' area.
  std::vector<double> dist(s.skin.deformed.size(), std::numeric_limits<double>::infinity()), w(dist.size(), 0.0);
  for (const auto& t : s.skin.triangles)
  {
    const Point &a = s.skin.deformed[t[0]], &b = s.skin.deformed[t[1]], &cc = s.skin.deformed[t[2]];
    const Point u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]};
    const double area = 0.5 * std::hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
    for (int k = 0; k < 3; ++k)
      w[t[k]] += area / 3;
  }
  for (std::size_t i = 0; i < dist.size(); ++i)
  {
    const Point& p = s.skin.deformed[i];
    for (const auto& t : tri)
    {
      const auto l = closest_barycentric(p, t[0], t[1], t[2]);
      dist[i] = std::min(dist[i], distance(p, barycentric_point(l, t[0], t[1], t[2])));
    }
  }
  double sum = 0, wsum = 0;
  for (std::size_t i = 0; i < dist.size(); ++i)
    sum += w[i] * dist[i], wsum += w[i];
  c.mean = sum / wsum;
  std::vector<double> sorted = dist;
  std::sort(sorted.begin(), sorted.end());
  c.p95 = sorted[static_cast<std::size_t>(0.95 * (sorted.size() - 1))];
  c.max = sorted.back();
  c.volume_scan = s.volume;
  c.volume_model = volume_under(model);
  return c;
}

Point onto_scan(const ScannedSkin& s, const Point& shift, const Point& p)
{
  Point d{p[0] + shift[0], std::max(0.0, p[1] + shift[1]), p[2] + shift[2]};
  d = (1 / scan::norm(d)) * d;
  const Point q = s.fit.radius(d) * d;
  return {q[0] - shift[0], q[1] - shift[1], q[2] - shift[2]};
}

nlohmann::json to_json(const ScanSide& s)
{
  const auto& c = s.comparison;
  return {{"file", s.input.file.filename().string()},
          {"points", s.skin.points},
          {"noise_rms_mm", 1e3 * s.skin.noise_rms},
          {"measured", to_json(s.measured.landmarks)},
          {"notch_given", s.measured.notch.has_value()},
          {"model_to_scan_mm", {{"mean", 1e3 * c.mean}, {"p95", 1e3 * c.p95}, {"max", 1e3 * c.max}}},
          {"volume_cm3", {{"scan", 1e6 * c.volume_scan}, {"model", 1e6 * c.volume_model}}},
          {"volume_error", c.volume_error()}};
}

nlohmann::json scan_surface_json(const ScannedSkin& s, const Point& shift)
{
  std::vector<double> v;
  std::vector<std::int32_t> t;
  for (const auto& p : s.skin.deformed)
    for (int k = 0; k < 3; ++k)
      v.push_back(std::round((p[k] - shift[k]) * 1e4) / 1e4);
  for (const auto& tri : s.skin.triangles)
    t.insert(t.end(), tri.begin(), tri.end());
  return {{"vertices", v}, {"triangles", t}, {"mirror_x", false}};
}
} // namespace breastsim::clinic
