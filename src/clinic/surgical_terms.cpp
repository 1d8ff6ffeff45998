// SPDX-License-Identifier: LGPL-3.0-or-later
#include "surgical_terms.hpp"
#include "errors.hpp"
#include "half_cap.hpp"
#include "on_root.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace breastsim::clinic
{
double resected_volume(const HalfCapSpec& cap, const meshes::IncisionGeometry& g, int n)
{
  const double R = cap.R, Rs = meshes::sphere_radius(cap.R, cap.H), yc = cap.H - Rs;
  const double dx = R / n, dz = 2 * R / (2 * n);
  double half = 0;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 2 * n; ++k)
    {
      const double x = (i + 0.5) * dx, z = -R + (k + 0.5) * dz;
      const double r2 = x * x + z * z;
      if (r2 >= R * R)
        continue;
      const double Y = yc + std::sqrt(Rs * Rs - r2); // skin height over (x, z)
      double length = 0;
      if (g.n1[0] * x + g.n1[2] * z < g.c1)
        length = Y; // the keel: the whole column
      else if (std::abs(g.n2[1]) > 1e-14)
      {
        // n2y y + n2z z < c2: below or above y* = (c2 - n2z z) / n2y.
        const double ys = std::clamp((g.c2 - g.n2[2] * z) / g.n2[1], 0.0, Y);
        length = g.n2[1] > 0 ? ys : Y - ys;
      }
      else if (g.n2[2] * z < g.c2)
        length = Y;
      half += length * dx * dz;
    }
  return 2 * half;
}

namespace
{
/// The standing positions of neutral points of the right half (x >= 0); a
/// point with x < 0 is carried by its mirror image and mirrored back.
std::vector<Point> standing_positions(const SkinSurface& standing, const std::vector<Point>& neutral)
{
  std::vector<Point> out;
  for (const auto& p : neutral)
  {
    const double sign = p[0] < 0 ? -1 : 1;
    Point q = deformed_position(standing, {sign * p[0], p[1], p[2]});
    q[0] *= sign;
    out.push_back(q);
  }
  return out;
}

std::vector<Point> mirrored(std::vector<Point> p)
{
  for (auto& q : p)
    q[0] = -q[0];
  return p;
}
} // namespace

std::vector<Point> limb_curve(const HalfCapSpec& cap, const IncisionSpec& in, int n)
{
  const auto g = meshes::incision_geometry(cap, in);
  const double Rs = meshes::sphere_radius(cap.R, cap.H), yc = cap.H - Rs;
  const double ta = std::tan(in.a_deg * M_PI / 180);
  std::vector<Point> p;
  for (int k = 0; k <= n; ++k)
  {
    const double z = g.A[2] + (g.D[2] - g.A[2]) * k / n, x = (in.s - z) * ta; // on P1
    p.push_back({x, yc + std::sqrt(std::max(0.0, Rs * Rs - x * x - z * z)), z});
  }
  return p;
}

std::vector<Point> p2_curve(const HalfCapSpec& cap, const IncisionSpec& in, int n)
{
  const auto g = meshes::incision_geometry(cap, in);
  const double Rs = meshes::sphere_radius(cap.R, cap.H), yc = cap.H - Rs, d = in.d;
  const double x_rim = std::sqrt(std::max(0.0, cap.R * cap.R - d * d));
  // In each plane x = const, P2's trace is (y, z) = (0, -d) + t (y_D, z_D + d);
  // on the sphere x^2 + (y - yc)^2 + z^2 = Rs^2: qa t^2 + qb t + qc = 0.
  const double ey = g.D[1], ez = g.D[2] + d;
  const double qa = ey * ey + ez * ez, qb = -2 * (yc * ey + d * ez);
  std::vector<Point> p;
  for (int k = 0; k <= n; ++k)
  {
    const double f = static_cast<double>(k) / n, x = g.D[0] + (x_rim - g.D[0]) * f;
    const double qc = x * x + yc * yc + d * d - Rs * Rs, disc = qb * qb - 4 * qa * qc;
    if (disc < 0)
      continue;
    // The root that runs from D (t = 1) to the rim (t = 0): nearest to 1 - f.
    const double t1 = (-qb + std::sqrt(disc)) / (2 * qa), t2 = (-qb - std::sqrt(disc)) / (2 * qa);
    const double t = std::abs(t1 - (1 - f)) < std::abs(t2 - (1 - f)) ? t1 : t2;
    p.push_back({x, std::max(0.0, t * ey), -d + t * ez});
  }
  return p;
}

std::vector<std::vector<Point>> wise_marking(const HalfCapSpec& cap, const IncisionSpec& in,
                                             const SkinSurface& standing)
{
  const auto limb = standing_positions(standing, limb_curve(cap, in));
  const auto arc = standing_positions(standing, p2_curve(cap, in));
  // The fold's incision: the base rim below z = -d, from one side to the other.
  const double start = std::asin(std::clamp(in.d / cap.R, 0.0, 1.0));
  std::vector<Point> rim;
  const int n = 60;
  for (int k = 0; k <= n; ++k)
  {
    const double phi = -start - (M_PI - 2 * start) * k / n; // from (x_rim, -d) through (0, -R) to (-x_rim, -d)
    rim.push_back({cap.R * std::cos(phi), 0.0, cap.R * std::sin(phi)});
  }
  return {limb, mirrored(limb), arc, mirrored(arc), standing_positions(standing, rim)};
}

SurgicalTerms surgical_terms(const HalfCapSpec& cap, const IncisionSpec& in, const SkinSurface& standing,
                             const Point& notch, double rho, MPI_Comm comm)
{
  const auto g = meshes::incision_geometry(cap, in);
  SurgicalTerms t;
  t.resection_grams = 1e3 * rho * resected_volume(cap, g);
  std::array<double, 2> v{};
  on_root(comm,
          [&]
          {
            v[0] = taut_tape(standing, notch, deformed_position(standing, g.A));
            v[1] = arc_length(standing_positions(standing, limb_curve(cap, in)), 0);
          });
  MPI_Bcast(v.data(), 2, MPI_DOUBLE, 0, comm);
  t.new_nipple_sn_n = v[0];
  t.vertical_limb = v[1];
  return t;
}

namespace
{
double keel_weight(const HalfCapSpec& cap, IncisionSpec in, double a_deg, double rho)
{
  in.a_deg = a_deg;
  return 1e3 * rho * resected_volume(cap, meshes::incision_geometry(cap, in), 300);
}
} // namespace

WeightRange weight_range(const HalfCapSpec& cap, IncisionSpec in, double rho)
{
  // The widest keel whose incision exists (B on the base, D on the skin).
  auto exists = [&](double a_deg)
  {
    try
    {
      in.a_deg = a_deg;
      meshes::incision_geometry(cap, in);
      return true;
    }
    catch (const InputError&)
    {
      return false;
    }
  };
  WeightRange w;
  w.a_min = 1.0;
  if (!exists(w.a_min))
    throw InputError(fmt::format("no incision exists with s = {:.1f} mm, h = {:.1f} mm, d = {:.1f} mm at any angle",
                                 1e3 * in.s, 1e3 * in.h, 1e3 * in.d));
  double lo = w.a_min, hi = 89.0;
  if (!exists(hi))
    for (int k = 0; k < 50; ++k)
      (exists(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  w.a_max = exists(hi) ? hi : lo;
  w.least = keel_weight(cap, in, w.a_min, rho);
  w.most = keel_weight(cap, in, w.a_max, rho);
  return w;
}

double angle_for_grams(const HalfCapSpec& cap, IncisionSpec in, double grams, double rho)
{
  const WeightRange w = weight_range(cap, in, rho);
  if (!(grams >= w.least && grams <= w.most))
    throw InputError(fmt::format("a resection of {:.0f} g is out of reach with s = {:.1f} mm, h = {:.1f} mm, "
                                 "d = {:.1f} mm: from {:.0f} g (a = {:.0f} deg) to {:.0f} g (a = {:.1f} deg)",
                                 grams, 1e3 * in.s, 1e3 * in.h, 1e3 * in.d, w.least, w.a_min, w.most, w.a_max));
  double lo = w.a_min, hi = w.a_max; // weight grows with the keel's angle
  for (int k = 0; k < 50 && hi - lo > 1e-6; ++k)
    (keel_weight(cap, in, 0.5 * (lo + hi), rho) < grams ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}
} // namespace breastsim::clinic
