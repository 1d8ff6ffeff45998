// SPDX-License-Identifier: LGPL-3.0-or-later
#include "field_ridge.hpp"
#include "errors.hpp"
#include "least_squares.hpp"
#include "uncertainty.hpp"
#include <cmath>
#include <limits>
#include <stdexcept>

namespace breastsim::diagnosis
{
namespace
{
/// The normal equations of one posture's rows of C = [A B]: G = C^T C,
/// g = C^T r, e = r^T r.
struct Gram
{
  Matrix G;
  std::vector<double> g;
  double e = 0;
};

Gram gram(const Matrix& A, const Matrix& B, const std::vector<double>& r,
          const std::vector<std::size_t>& rows, std::size_t ka, std::size_t kb)
{
  const std::size_t n = ka + kb;
  Gram out{Matrix(n, std::vector<double>(n, 0.0)), std::vector<double>(n, 0.0), 0.0};
  std::vector<double> c(n);
  for (std::size_t i : rows)
  {
    for (std::size_t j = 0; j < n; ++j)
      c[j] = j < ka ? A[i][j] : B[i][j - ka];
    for (std::size_t j = 0; j < n; ++j)
    {
      out.g[j] += c[j] * r[i];
      for (std::size_t k = 0; k < n; ++k)
        out.G[j][k] += c[j] * c[k];
    }
    out.e += r[i] * r[i];
  }
  return out;
}

/// chi2 of one posture at x: e + 2 x^T g + x^T G x.
double chi2_at(const Gram& p, const std::vector<double>& x)
{
  double s = p.e;
  for (std::size_t j = 0; j < x.size(); ++j)
  {
    s += 2 * x[j] * p.g[j];
    for (std::size_t k = 0; k < x.size(); ++k)
      s += x[j] * p.G[j][k] * x[k];
  }
  return s;
}

/// x = argmin over the postures `use` (use[p]), the first `ka` unknowns
/// penalised by lambda, the field's unknowns zero when `with_field` is false.
std::vector<double> solve_on(const std::vector<Gram>& parts, const std::vector<char>& use,
                             std::size_t ka, std::size_t n, double lambda, bool with_field,
                             const Matrix& mean_penalty)
{
  Matrix M(n, std::vector<double>(n, 0.0));
  std::vector<double> b(n, 0.0), x(n, 0.0);
  for (std::size_t p = 0; p < parts.size(); ++p)
    if (use[p])
      for (std::size_t j = 0; j < n; ++j)
      {
        b[j] -= parts[p].g[j];
        for (std::size_t k = 0; k < n; ++k)
          M[j][k] += parts[p].G[j][k];
      }
  for (std::size_t j = 0; j < ka && with_field && !mean_penalty.empty(); ++j)
    for (std::size_t k = 0; k < ka; ++k)
      M[j][k] += mean_penalty[j][k];
  for (std::size_t j = 0; j < ka; ++j)
  {
    M[j][j] += with_field ? lambda : 1.0;
    if (!with_field) // a = 0: decouple its unknowns
    {
      b[j] = 0;
      for (std::size_t k = 0; k < n; ++k)
        if (k != j)
          M[j][k] = M[k][j] = 0;
    }
  }
  if (!calibration::solve_dense(M, b, x))
    throw SolveError("the field's linearised fit is singular");
  return x;
}

/// Effective parameters of the field at lambda: tr((G + lambda D)^-1 G) - kb.
double effective_dof(const std::vector<Gram>& parts, std::size_t ka, std::size_t n, double lambda,
                     const Matrix& mean_penalty)
{
  Matrix G(n, std::vector<double>(n, 0.0));
  for (const auto& p : parts)
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t k = 0; k < n; ++k)
        G[j][k] += p.G[j][k];
  Matrix M = G;
  for (std::size_t j = 0; j < ka; ++j)
  {
    M[j][j] += lambda;
    for (std::size_t k = 0; k < ka && !mean_penalty.empty(); ++k)
      M[j][k] += mean_penalty[j][k];
  }
  if (!calibration::invert_spd(M))
    return static_cast<double>(ka);
  double tr = 0;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < n; ++k)
      tr += M[j][k] * G[k][j];
  return tr - static_cast<double>(n - ka);
}
} // namespace

RidgeChoice choose_ridge(const Matrix& A, const Matrix& B, const std::vector<double>& r,
                         const std::vector<std::vector<std::size_t>>& rows,
                         const std::vector<double>& mean_weights)
{
  if (rows.size() < 2 || A.empty() || A[0].empty())
    throw std::logic_error("choose_ridge: needs two postures and a field column");
  const std::size_t ka = A[0].size(), kb = B.empty() ? 0 : B[0].size(), n = ka + kb;
  std::vector<Gram> parts;
  for (const auto& pr : rows)
    parts.push_back(gram(A, B, r, pr, ka, kb));
  double scale = 0;
  for (const auto& p : parts)
    for (std::size_t j = 0; j < ka; ++j)
      scale += p.G[j][j] / static_cast<double>(ka);
  Matrix mean_penalty; // zero_mean_weight s m m^T
  if (!mean_weights.empty())
  {
    mean_penalty.assign(ka, std::vector<double>(ka, 0.0));
    for (std::size_t j = 0; j < ka; ++j)
      for (std::size_t k = 0; k < ka; ++k)
        mean_penalty[j][k] = zero_mean_weight * scale * mean_weights[j] * mean_weights[k];
  }
  RidgeChoice best;
  best.total_gain = -std::numeric_limits<double>::infinity();
  for (int j = -6; j <= 8; ++j)
  {
    const double lambda = scale * std::pow(10.0, 0.5 * j);
    std::vector<double> gains;
    double total = 0;
    for (std::size_t p = 0; p < parts.size(); ++p)
    {
      std::vector<char> use(parts.size(), 1);
      use[p] = 0;
      const auto with = solve_on(parts, use, ka, n, lambda, true, mean_penalty);
      const auto without = solve_on(parts, use, ka, n, lambda, false, mean_penalty);
      gains.push_back(chi2_at(parts[p], without) - chi2_at(parts[p], with));
      total += gains.back();
    }
    best.path.emplace_back(lambda, total);
    if (total > best.total_gain)
    {
      best.total_gain = total;
      best.lambda = lambda;
      best.held_out_gain = gains;
    }
  }
  const auto x = solve_on(parts, std::vector<char>(parts.size(), 1), ka, n, best.lambda, true, mean_penalty);
  best.a.assign(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(ka));
  best.d.assign(x.begin() + static_cast<std::ptrdiff_t>(ka), x.end());
  best.scale = scale;
  best.dof = effective_dof(parts, ka, n, best.lambda, mean_penalty);
  return best;
}
} // namespace breastsim::diagnosis
