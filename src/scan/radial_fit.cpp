// SPDX-License-Identifier: LGPL-3.0-or-later
#include "radial_fit.hpp"
#include "scan_linalg.hpp"
#include <algorithm>
#include <cmath>

namespace breastsim::scan
{
namespace
{
/// T_0(x) .. T_n(x): T_{k+1} = 2 x T_k - T_{k-1}.
std::vector<double> chebyshev(double x, int n)
{
  std::vector<double> t(n + 1, 1.0);
  if (n >= 1)
    t[1] = x;
  for (int k = 1; k < n; ++k)
    t[k + 1] = 2 * x * t[k] - t[k - 1];
  return t;
}

/// The basis T_i(p) T_j(q), i + j <= n, in the order of RadialSurface::coef.
std::vector<double> basis(double p, double q, int n)
{
  const std::vector<double> tp = chebyshev(p, n), tq = chebyshev(q, n);
  std::vector<double> b;
  b.reserve((n + 1) * (n + 2) / 2);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j)
      b.push_back(tp[i] * tq[j]);
  return b;
}
} // namespace

std::array<double, 2> disk_coords(const Vec3& d)
{
  const double alpha = std::acos(std::clamp(d[1], -1.0, 1.0)), beta = std::atan2(d[2], d[0]);
  const double rho = 2 * alpha / M_PI;
  return {rho * std::cos(beta), rho * std::sin(beta)};
}

Vec3 disk_direction(double p, double q)
{
  const double rho = std::hypot(p, q), alpha = 0.5 * M_PI * rho;
  // sin(alpha) / rho -> pi / 2 at the centre
  const double k = rho > 1e-12 ? std::sin(alpha) / rho : 0.5 * M_PI;
  return {k * p, std::cos(alpha), k * q};
}

double RadialSurface::radius(double p, double q) const
{
  const std::vector<double> b = basis(p, q, degree);
  double r = 0;
  for (std::size_t k = 0; k < b.size(); ++k)
    r += coef[k] * b[k];
  return r;
}

double RadialSurface::radius(const Vec3& d) const
{
  const auto [p, q] = disk_coords(d);
  return radius(p, q);
}

RadialSurface fit_radial(const std::vector<Vec3>& points, int degree, double smoothing)
{
  const std::size_t n = (degree + 1) * (degree + 2) / 2;
  std::vector<double> A(n * n, 0.0), rhs(n, 0.0);
  for (const Vec3& x : points)
  {
    const double r = norm(x);
    const auto [p, q] = disk_coords((1 / r) * x);
    const std::vector<double> b = basis(p, q, degree);
    for (std::size_t i = 0; i < n; ++i)
    {
      rhs[i] += b[i] * r;
      for (std::size_t j = 0; j <= i; ++j)
        A[i * n + j] += b[i] * b[j];
    }
  }
  double trace = 0;
  for (std::size_t i = 0; i < n; ++i)
    trace += A[i * n + i];
  std::size_t k = 0;
  for (int i = 0; i <= degree; ++i)
    for (int j = 0; i + j <= degree; ++j, ++k) // penalty lambda (i + j)^4 c_ij^2
      A[k * n + k] += smoothing * trace / n * std::pow(i + j, 4) + 1e-12 * trace / n;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      A[i * n + j] = A[j * n + i];
  return {degree, cholesky_solve(A, rhs)};
}

double radial_volume(const RadialSurface& f)
{
  // V = int_0^{pi/2} int_0^{2 pi} r^3 / 3 sin(alpha) dbeta dalpha (midpoint rule)
  const int na = 90, nb = 180;
  double v = 0;
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nb; ++j)
    {
      const double alpha = (i + 0.5) * 0.5 * M_PI / na, beta = (j + 0.5) * 2 * M_PI / nb;
      const double rho = 2 * alpha / M_PI, r = f.radius(rho * std::cos(beta), rho * std::sin(beta));
      v += r * r * r / 3 * std::sin(alpha) * (0.5 * M_PI / na) * (2 * M_PI / nb);
    }
  return v;
}

std::vector<double> radial_residuals(const RadialSurface& f, const std::vector<Vec3>& points)
{
  std::vector<double> r(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const double len = norm(points[i]);
    r[i] = len - f.radius((1 / len) * points[i]);
  }
  return r;
}
} // namespace breastsim::scan
