// SPDX-License-Identifier: LGPL-3.0-or-later
#include "least_squares.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace breastsim::calibration
{
namespace
{
double sum_squares(const std::vector<double>& r)
{
  double s = 0;
  for (double x : r)
    s += x * x;
  return s;
}

/// Damped steps (J^T J + lambda diag(J^T J)) dy = -J^T r from res.y, clamped
/// to the bounds, until one decreases chi2 (lambda / 3 after it, x 4 after
/// each rejected one; res moves there), or the rejected steps are shorter
/// than min_step in every ln p (a minimum within that resolution), or
/// max_trials were rejected. max_step: the largest |dy| of the accepted
/// step; decrease: its relative decrease of chi2.
bool damped_step(const ResidualFunction& f, const Matrix& A, const std::vector<double>& g,
                 const std::vector<double>& lo, const std::vector<double>& hi, double min_step,
                 int max_evaluations, LsqResult& res, double& lambda, double& max_step,
                 double& decrease)
{
  constexpr int max_trials = 16;
  const std::size_t n = g.size();
  for (int attempt = 0; attempt < max_trials; ++attempt)
  {
    if (max_evaluations > 0 && res.evaluations >= max_evaluations)
      return false;
    const auto step = gauss_newton_step(A, g, lambda);
    if (!step) // singular
    {
      lambda *= 4;
      continue;
    }
    const std::vector<double>& dy = *step;
    auto y1 = res.y;
    max_step = 0;
    for (std::size_t a = 0; a < n; ++a)
    {
      y1[a] = std::clamp(res.y[a] + dy[a], lo[a], hi[a]);
      max_step = std::max(max_step, std::abs(y1[a] - res.y[a]));
    }
    if (max_step == 0 || (attempt > 0 && max_step < min_step))
      return false;
    const auto r1 = f(y1);
    ++res.evaluations;
    const double chi2 = sum_squares(r1);
    if (chi2 < res.chi2)
    {
      decrease = (res.chi2 - chi2) / std::max(res.chi2, 1e-300);
      res.y = y1;
      res.r = r1;
      res.chi2 = chi2;
      lambda = std::max(lambda / 3, 1e-9);
      return true;
    }
    lambda *= 4;
  }
  return false;
}

/// The decrease of chi2 the Gauss-Newton model |r + J dy|^2 predicts for its
/// step dy = -(J^T J)^-1 J^T r clamped to the bounds:
///     -(2 g.dy + dy.A dy),  A = J^T J, g = J^T r  (0 if A is singular).
double gauss_newton_decrease(const Matrix& A, const std::vector<double>& g, const std::vector<double>& y,
                             const std::vector<double>& lo, const std::vector<double>& hi)
{
  const std::size_t n = g.size();
  const auto step = gauss_newton_step(A, g);
  if (!step)
    return 0;
  auto dy = *step;
  for (std::size_t a = 0; a < n; ++a)
    dy[a] = std::clamp(y[a] + dy[a], lo[a], hi[a]) - y[a];
  double change = 0;
  for (std::size_t a = 0; a < n; ++a)
  {
    change += 2 * g[a] * dy[a];
    for (std::size_t b = 0; b < n; ++b)
      change += dy[a] * A[a][b] * dy[b];
  }
  return -change;
}

/// After a short step (below o.xtol, or a relative decrease below
/// o.ftol_rel): res.J becomes the Jacobian at res.y, and the fit has
/// converged if the Gauss-Newton model there predicts at most o.chi2_tol
/// further decrease (res.stop_reason says so).
bool converged_after_short_step(const JacobianFunction& jacobian, const std::vector<double>& lo,
                                const std::vector<double>& hi, const LsqOptions& o,
                                double max_step, LsqResult& res)
{
  res.J = jacobian(res.y, res.r, res.evaluations);
  Matrix A;
  std::vector<double> g;
  normal_equations(res.J, res.r, res.y.size(), A, g);
  const double predicted = gauss_newton_decrease(A, g, res.y, lo, hi);
  if (predicted > o.chi2_tol)
    return false;
  const std::string why = max_step < o.xtol
                              ? fmt::format("step below {:g} in ln p", o.xtol)
                              : fmt::format("chi2 decreased by less than {:g} (relative)", o.ftol_rel);
  res.stop_reason =
      fmt::format("{}; the Gauss-Newton model predicts chi2 to fall by {:.2g} more", why, predicted);
  return true;
}
} // namespace

std::optional<std::vector<double>> gauss_newton_step(const Matrix& A, const std::vector<double>& g,
                                                     double lambda)
{
  const std::size_t n = g.size();
  Matrix M = A;
  std::vector<double> minus_g(n), dy;
  for (std::size_t a = 0; a < n; ++a)
  {
    M[a][a] += lambda * std::max(A[a][a], 1e-12);
    minus_g[a] = -g[a];
  }
  if (!solve_dense(std::move(M), std::move(minus_g), dy))
    return std::nullopt;
  return dy;
}

bool solve_dense(Matrix A, std::vector<double> b, std::vector<double>& x)
{
  const std::size_t n = b.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    std::size_t p = k;
    for (std::size_t i = k + 1; i < n; ++i)
      if (std::abs(A[i][k]) > std::abs(A[p][k]))
        p = i;
    double scale = 0;
    for (std::size_t i = 0; i < n; ++i)
      scale = std::max(scale, std::abs(A[i][k]));
    if (!(std::abs(A[p][k]) > 1e-14 * scale) || scale == 0)
      return false;
    std::swap(A[k], A[p]);
    std::swap(b[k], b[p]);
    for (std::size_t i = k + 1; i < n; ++i)
    {
      const double f = A[i][k] / A[k][k];
      for (std::size_t j = k; j < n; ++j)
        A[i][j] -= f * A[k][j];
      b[i] -= f * b[k];
    }
  }
  x.assign(n, 0.0);
  for (std::size_t k = n; k-- > 0;)
  {
    double s = b[k];
    for (std::size_t j = k + 1; j < n; ++j)
      s -= A[k][j] * x[j];
    x[k] = s / A[k][k];
  }
  return true;
}

Matrix fd_jacobian(const ResidualFunction& f, const std::vector<double>& y,
                   const std::vector<double>& r0, double step, int& evaluations,
                   const CaseGroups* groups)
{
  // Column j: J_ij = (r_i(y + h e_j) - r_i(y)) / h.
  auto column = [&](std::size_t j)
  {
    auto yp = y;
    yp[j] += step;
    return f(yp);
  };
  std::vector<std::vector<double>> rp(y.size());
  if (groups)
    rp = groups->map(y.size(), column);
  else
    for (std::size_t j = 0; j < y.size(); ++j)
      rp[j] = column(j);
  evaluations += static_cast<int>(y.size());
  Matrix J(r0.size(), std::vector<double>(y.size()));
  for (std::size_t j = 0; j < y.size(); ++j)
    for (std::size_t i = 0; i < r0.size(); ++i)
      J[i][j] = (rp[j][i] - r0[i]) / step;
  return J;
}

LsqResult levenberg_marquardt(const ResidualFunction& f, std::vector<double> y0,
                              const std::vector<double>& lo, const std::vector<double>& hi,
                              const LsqOptions& o,
                              const std::function<void(int, double, const std::vector<double>&)>& progress,
                              const JacobianFunction& exact)
{
  const JacobianFunction jacobian =
      exact ? exact
            : JacobianFunction([&](const std::vector<double>& y, const std::vector<double>& r, int& evaluations)
                               { return fd_jacobian(f, y, r, o.fd_step, evaluations, o.groups); });
  const std::size_t n = y0.size();
  LsqResult res;
  for (std::size_t j = 0; j < n; ++j)
    y0[j] = std::clamp(y0[j], lo[j], hi[j]);
  res.y = y0;
  res.r = f(res.y);
  ++res.evaluations;
  res.chi2 = sum_squares(res.r);
  double lambda = 1e-3;
  bool have_J = false;
  res.stop_reason = "maximum number of iterations";
  for (int it = 0; it < o.max_iterations; ++it)
  {
    if (!have_J)
    {
      res.J = jacobian(res.y, res.r, res.evaluations);
      have_J = true;
    }
    Matrix A;
    std::vector<double> g;
    normal_equations(res.J, res.r, n, A, g);
    double max_step = 0, decrease = 0;
    if (!damped_step(f, A, g, lo, hi, o.xtol / 10, o.max_evaluations, res, lambda, max_step,
                     decrease))
    {
      res.stop_reason = o.max_evaluations > 0 && res.evaluations >= o.max_evaluations
                            ? "evaluation budget used up"
                            : "no step decreases chi2 (at a minimum within the bounds)";
      break;
    }
    have_J = false;
    res.iterations = it + 1;
    if (progress)
      progress(res.iterations, res.chi2, res.y);
    if (max_step >= o.xtol && decrease >= o.ftol_rel)
      continue;
    have_J = true;
    if (converged_after_short_step(jacobian, lo, hi, o, max_step, res))
      break;
    lambda = std::min(lambda, 1e-3); // the damping, not the optimum, made the step short
  }
  if (!have_J) // Jacobian at the final point (uncertainty, score tests)
    res.J = jacobian(res.y, res.r, res.evaluations);
  return res;
}

void normal_equations(const Matrix& J, const std::vector<double>& r, std::size_t n, Matrix& A,
                      std::vector<double>& g)
{
  A.assign(n, std::vector<double>(n, 0.0));
  g.assign(n, 0.0);
  for (std::size_t i = 0; i < r.size(); ++i)
    for (std::size_t a = 0; a < n; ++a)
    {
      g[a] += J[i][a] * r[i];
      for (std::size_t b = 0; b < n; ++b)
        A[a][b] += J[i][a] * J[i][b];
    }
}

} // namespace breastsim::calibration
