// SPDX-License-Identifier: LGPL-3.0-or-later
#include "chest_curvature.hpp"
#include "errors.hpp"
#include "scan_linalg.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace breastsim::scan
{
namespace
{
/// The chest surface's points (breast frame) within `radius` of the chest
/// normal through the origin: its vertices and, on triangles larger than
/// `spacing`, points of a barycentric grid of that spacing.
std::vector<Vec3> chest_samples(const BreastFrame& f, const ScanSurface& chest, double radius, double spacing)
{
  std::vector<Vec3> out;
  auto keep = [&](const Vec3& scanner_point)
  {
    const Vec3 q = f.to_breast(scanner_point);
    if (std::hypot(q[0], q[2]) <= radius)
      out.push_back(q);
  };
  for (const Vec3& p : chest.points)
    keep(p);
  for (const Triangle& t : chest.triangles)
  {
    const Vec3 &a = chest.points[t[0]], &b = chest.points[t[1]], &c = chest.points[t[2]];
    const double edge = std::max({norm(b - a), norm(c - b), norm(a - c)});
    const int k = std::min(200, static_cast<int>(std::ceil(edge / spacing)));
    for (int i = 0; i <= k && k > 1; ++i)
      for (int j = 0; i + j <= k; ++j)
        if ((i > 0 || j > 0) && i < k && j < k) // the grid's interior and edges, not the corners
          keep(a + (double(i) / k) * (b - a) + (double(j) / k) * (c - a));
  }
  return out;
}

/// Least-squares quadric graph y = c0 + c1 x + c2 z + c3 x^2 + c4 x z + c5 z^2.
std::vector<double> fit_quadric(const std::vector<Vec3>& q)
{
  std::vector<double> A(36, 0.0), b(6, 0.0);
  for (const Vec3& p : q)
  {
    const double phi[6] = {1, p[0], p[2], p[0] * p[0], p[0] * p[2], p[2] * p[2]};
    for (int r = 0; r < 6; ++r)
    {
      b[r] += phi[r] * p[1];
      for (int c = 0; c < 6; ++c)
        A[6 * r + c] += phi[r] * phi[c];
    }
  }
  return cholesky_solve(A, b);
}

double quadric_at(const std::vector<double>& c, double x, double z)
{
  return c[0] + c[1] * x + c[2] * z + c[3] * x * x + c[4] * x * z + c[5] * z * z;
}

/// Curvatures below this [1/m] (radii above 1 km) are flat.
constexpr double flat_curvature = 1e-3;

/// Signed principal radii -1 / kappa of the graph's Hessian [[2 c3, c4], [c4, 2 c5]]
/// (> 0: bulging toward +y, the breast), the smaller magnitude first.
std::array<double, 2> principal_radii(const std::vector<double>& c)
{
  const double mean = c[3] + c[5];
  const double half_gap = std::hypot(c[3] - c[5], 0.5 * c[4]);
  std::array<double, 2> r;
  const double kappa[2] = {mean - half_gap, mean + half_gap};
  for (int k = 0; k < 2; ++k)
    r[k] = std::abs(kappa[k]) < flat_curvature ? std::numeric_limits<double>::infinity() : -1.0 / kappa[k];
  if (std::abs(r[0]) > std::abs(r[1]))
    std::swap(r[0], r[1]);
  return r;
}
} // namespace

ChestCurvature measure_chest(const BreastFrame& f, const ScanSurface& skin, const ScanSurface* chest)
{
  ChestCurvature out;
  std::vector<Vec3> q;
  if (chest)
  {
    out.source = "chest surface";
    q = chest_samples(f, *chest, 1.2 * f.footprint_radius, f.footprint_radius / 15);
    if (q.size() < 12)
      throw InputError(fmt::format("{}: the chest surface does not cover the breast: {} of its points lie within "
                                   "{:.1f} mm (1.2 footprint radii) of the footprint's centre (at least 12)",
                                   chest->where, q.size(), 1e3 * 1.2 * f.footprint_radius));
  }
  else
  {
    out.source = "footprint";
    for (auto v : f.footprint)
      q.push_back(f.to_breast(skin.points[v]));
  }
  out.samples = q.size();
  double sum = 0;
  for (const Vec3& p : q)
  {
    sum += p[1] * p[1]; // the plane is y = 0
    out.plane_max = std::max(out.plane_max, std::abs(p[1]));
  }
  out.plane_rms = q.empty() ? 0 : std::sqrt(sum / q.size());
  if (!chest)
    return out;
  std::vector<double> c;
  try
  {
    c = fit_quadric(q);
  }
  catch (const std::runtime_error&) // the samples lie on a curve: no quadric to report
  {
    return out;
  }
  double qsum = 0;
  for (const Vec3& p : q)
    qsum += std::pow(p[1] - quadric_at(c, p[0], p[2]), 2);
  out.quadric = true;
  out.quadric_rms = std::sqrt(qsum / q.size());
  out.curvature_radii = principal_radii(c);
  return out;
}

void check_chest_curvature(const ChestCurvature& c, double max_rms, const std::string& where)
{
  if (c.plane_rms > max_rms)
    throw InputError(fmt::format(
        "{}: chest too curved for a planar base: the chest wall ({}, {} points under the breast) lies {:.2f} mm "
        "RMS (up to {:.1f} mm) off the fitted chest plane, above --max-chest-rms = {:.2f} mm",
        where, c.source, c.samples, 1e3 * c.plane_rms, 1e3 * c.plane_max, 1e3 * max_rms));
}
} // namespace breastsim::scan
