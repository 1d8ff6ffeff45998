// SPDX-License-Identifier: LGPL-3.0-or-later
#include "uncertainty.hpp"
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace breastsim::calibration
{
bool invert_spd(Matrix& A)
{
  const std::size_t n = A.size();
  double scale = 0;
  for (std::size_t i = 0; i < n; ++i)
    scale = std::max(scale, std::abs(A[i][i]));
  Matrix inv(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i)
    inv[i][i] = 1;
  for (std::size_t col = 0; col < n; ++col)
  {
    std::size_t piv = col;
    for (std::size_t r = col + 1; r < n; ++r)
      if (std::abs(A[r][col]) > std::abs(A[piv][col]))
        piv = r;
    if (!(std::abs(A[piv][col]) > 1e-13 * scale))
      return false;
    std::swap(A[piv], A[col]);
    std::swap(inv[piv], inv[col]);
    const double d = A[col][col];
    for (std::size_t k = 0; k < n; ++k)
    {
      A[col][k] /= d;
      inv[col][k] /= d;
    }
    for (std::size_t r = 0; r < n; ++r)
      if (r != col && A[r][col] != 0)
      {
        const double f = A[r][col];
        for (std::size_t k = 0; k < n; ++k)
        {
          A[r][k] -= f * A[col][k];
          inv[r][k] -= f * inv[col][k];
        }
      }
  }
  A = inv;
  return true;
}

void widen_interval(Uncertainty& u, std::size_t i, double p, double se_extra)
{
  u.se_log[i] = std::hypot(u.se_log[i], se_extra);
  u.interval[i] = {p * std::exp(-1.96 * u.se_log[i]), p * std::exp(1.96 * u.se_log[i])};
}

Uncertainty gauss_newton_uncertainty(const Matrix& J, const std::vector<double>& y,
                                     const std::vector<std::string>& names,
                                     double variance_factor)
{
  const std::size_t n = y.size();
  const double inf = std::numeric_limits<double>::infinity();
  Matrix C(n, std::vector<double>(n, 0.0)); // J^T J
  for (const auto& row : J)
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = 0; b < n; ++b)
        C[a][b] += row[a] * row[b];
  Uncertainty u;
  u.flags.assign(n, "");
  u.correlation.assign(n, std::vector<double>(n, std::nan("")));
  u.singular = !invert_spd(C);
  for (std::size_t j = 0; j < n; ++j)
  {
    const double se = u.singular ? inf : std::sqrt(variance_factor * std::max(C[j][j], 0.0));
    u.se_log.push_back(se);
    u.interval.push_back({std::exp(y[j] - 1.96 * se), std::exp(y[j] + 1.96 * se)});
    if (u.singular)
      u.flags[j] = "not identifiable: the measurements do not constrain the fitted parameters "
                   "independently (J^T J is singular)";
    else if (se > max_se_log)
      u.flags[j] = fmt::format("poorly determined: relative standard error {:.0f} %", 100 * se);
  }
  if (u.singular)
    return u;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b)
    {
      u.correlation[a][b] = variance_factor * C[a][b] / (u.se_log[a] * u.se_log[b]);
      if (a != b && std::abs(u.correlation[a][b]) > max_correlation)
      {
        const std::string f = fmt::format("correlated with {} (r = {:.3f}): only a combination "
                                          "of both is determined",
                                          names[b], u.correlation[a][b]);
        u.flags[a] += (u.flags[a].empty() ? "" : "; ") + f;
      }
    }
  return u;
}
} // namespace breastsim::calibration
