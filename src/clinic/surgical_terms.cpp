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
/// Length of the standing positions of the neutral skin curve P1 from A down to D.
double limb_length(const HalfCapSpec& cap, const IncisionSpec& in, const meshes::IncisionGeometry& g,
                   const SkinSurface& standing)
{
  const double Rs = meshes::sphere_radius(cap.R, cap.H), yc = cap.H - Rs;
  const double ta = std::tan(in.a_deg * M_PI / 180);
  const int n = 120;
  double L = 0;
  Point prev{};
  for (int k = 0; k <= n; ++k)
  {
    const double z = g.A[2] + (g.D[2] - g.A[2]) * k / n, x = (in.s - z) * ta;
    const Point p{x, yc + std::sqrt(std::max(0.0, Rs * Rs - x * x - z * z)), z};
    const Point q = deformed_position(standing, p);
    if (k > 0)
      L += std::hypot(q[0] - prev[0], q[1] - prev[1], q[2] - prev[2]);
    prev = q;
  }
  return L;
}
} // namespace

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
            v[1] = limb_length(cap, in, g, standing);
          });
  MPI_Bcast(v.data(), 2, MPI_DOUBLE, 0, comm);
  t.new_nipple_sn_n = v[0];
  t.vertical_limb = v[1];
  return t;
}

double angle_for_grams(const HalfCapSpec& cap, IncisionSpec in, double grams, double rho)
{
  auto weight = [&](double a_deg)
  {
    in.a_deg = a_deg;
    return 1e3 * rho * resected_volume(cap, meshes::incision_geometry(cap, in), 300);
  };
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
  const double a_min = 1.0;
  if (!exists(a_min))
    throw InputError(fmt::format("no incision exists with s = {:.1f} mm, h = {:.1f} mm, d = {:.1f} mm at any angle",
                                 1e3 * in.s, 1e3 * in.h, 1e3 * in.d));
  double lo = a_min, hi = 89.0;
  if (!exists(hi))
    for (int k = 0; k < 50; ++k)
      (exists(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  const double a_max = exists(hi) ? hi : lo;
  const double least = weight(a_min), most = weight(a_max);
  if (!(grams >= least && grams <= most))
    throw InputError(fmt::format("a resection of {:.0f} g is out of reach with s = {:.1f} mm, h = {:.1f} mm, "
                                 "d = {:.1f} mm: from {:.0f} g (a = {:.0f} deg) to {:.0f} g (a = {:.1f} deg)",
                                 grams, 1e3 * in.s, 1e3 * in.h, 1e3 * in.d, least, a_min, most, a_max));
  lo = a_min, hi = a_max; // weight grows with the keel's angle
  for (int k = 0; k < 50 && hi - lo > 1e-6; ++k)
    (weight(0.5 * (lo + hi)) < grams ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}
} // namespace breastsim::clinic
