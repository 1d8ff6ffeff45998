// SPDX-License-Identifier: LGPL-3.0-or-later
#include "synthetic_breast.hpp"
#include "errors.hpp"
#include <cmath>

namespace breastsim::scan
{
namespace
{
void check(double v, double lo, double hi, const char* name)
{
  if (!(v >= lo && v <= hi))
    throw InputError(fmt::format("{} = {} is out of range: allowed [{}, {}]", name, v, lo, hi));
}

/// g(x) - 1 of the header (negative inside), unit footprint semi-axis a = 1.
double inside(const Vec3& x, const SyntheticShape& s)
{
  const double a = 1, c = 1.1, b = s.aspect, y0 = 0.25 * b;
  const double t = x[1] / b;
  const double xi = x[0] - s.lateral * a * t, zeta = x[2] + s.ptosis * c * t * t;
  const double as = xi > 0 ? a * (1 + s.asymmetry) : a * (1 - 0.5 * s.asymmetry);
  const double cs = zeta > 0 ? c * (1 - 0.5 * s.asymmetry) : c * (1 + 0.5 * s.asymmetry);
  return (xi / as) * (xi / as) + ((x[1] + y0) / b) * ((x[1] + y0) / b) + (zeta / cs) * (zeta / cs) - 1;
}

/// First crossing of g = 1 along the ray t d (steps, then bisection).
double ray_radius(const Vec3& d, const SyntheticShape& s)
{
  double lo = 0, hi = 0.01;
  while (inside(hi * d, s) < 0)
  {
    lo = hi;
    hi += 0.01;
    if (hi > 10)
      throw std::logic_error("synthetic_reference: the ray leaves no shape");
  }
  for (int k = 0; k < 60; ++k)
  {
    const double mid = 0.5 * (lo + hi);
    (inside(mid * d, s) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}
} // namespace

RadialSurface synthetic_reference(const SyntheticShape& s)
{
  check(s.volume * (1 + 1e-12), 200e-6, 1500e-6 * (1 + 2e-12), "volume [m^3]"); // 200 cm^3 * 1e-6 rounds below 2e-4
  check(s.ptosis, 0, 0.8, "ptosis");
  check(s.lateral, -0.4, 0.4, "lateral");
  check(s.asymmetry, 0, 0.4, "asymmetry");
  check(s.aspect, 0.4, 1.2, "aspect");
  std::vector<Vec3> points;
  const int n = 80;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
    {
      const double p = -1 + 2.0 * i / n, q = -1 + 2.0 * j / n;
      if (std::hypot(p, q) > 1)
        continue;
      const Vec3 d = disk_direction(p, q);
      points.push_back(ray_radius(d, s) * d);
    }
  RadialSurface f = fit_radial(points, 12, 1e-9);
  const double k = std::cbrt(s.volume / radial_volume(f)); // lengths scale as V^(1/3)
  for (double& c : f.coef)
    c *= k;
  return f;
}
} // namespace breastsim::scan
