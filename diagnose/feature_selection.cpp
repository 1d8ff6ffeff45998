// SPDX-License-Identifier: LGPL-3.0-or-later
#include "feature_selection.hpp"
#include "least_squares.hpp"
#include <cmath>
#include <limits>
#include <stdexcept>

namespace breastsim::diagnosis
{
namespace
{
/// One posture's normal equations of C = [A B]: G = C^T C, g = C^T r, e = r^T r.
struct Part
{
  Matrix G;
  std::vector<double> g;
  double e = 0;
};

Part part_of(const Matrix& A, const Matrix& B, const std::vector<double>& r,
             const std::vector<std::size_t>& rows)
{
  const std::size_t ka = A[0].size(), kb = B.empty() ? 0 : B[0].size(), n = ka + kb;
  Part p{Matrix(n, std::vector<double>(n, 0.0)), std::vector<double>(n, 0.0), 0.0};
  std::vector<double> c(n);
  for (std::size_t i : rows)
  {
    for (std::size_t j = 0; j < n; ++j)
      c[j] = j < ka ? A[i][j] : B[i][j - ka];
    for (std::size_t j = 0; j < n; ++j)
    {
      p.g[j] += c[j] * r[i];
      for (std::size_t k = 0; k < n; ++k)
        p.G[j][k] += c[j] * c[k];
    }
    p.e += r[i] * r[i];
  }
  return p;
}

/// x over the columns idx minimising the chi2 of the parts in use (a tiny
/// relative ridge keeps a column that moves nothing solvable).
std::vector<double> fit_on(const std::vector<Part>& parts, const std::vector<char>& use,
                           const std::vector<std::size_t>& idx)
{
  const std::size_t n = idx.size();
  Matrix M(n, std::vector<double>(n, 0.0));
  std::vector<double> b(n, 0.0), x;
  for (std::size_t p = 0; p < parts.size(); ++p)
    if (use[p])
      for (std::size_t j = 0; j < n; ++j)
      {
        b[j] -= parts[p].g[idx[j]];
        for (std::size_t k = 0; k < n; ++k)
          M[j][k] += parts[p].G[idx[j]][idx[k]];
      }
  for (std::size_t j = 0; j < n; ++j)
    M[j][j] *= 1 + 1e-10;
  if (!calibration::solve_dense(M, b, x))
    x.assign(n, 0.0);
  return x;
}

/// chi2 of one part at x over the columns idx: e + 2 x^T g + x^T G x.
double chi2_at(const Part& p, const std::vector<std::size_t>& idx, const std::vector<double>& x)
{
  double s = p.e;
  for (std::size_t j = 0; j < idx.size(); ++j)
  {
    s += 2 * x[j] * p.g[idx[j]];
    for (std::size_t k = 0; k < idx.size(); ++k)
      s += x[j] * p.G[idx[j]][idx[k]] * x[k];
  }
  return s;
}

/// Every subset of {0 .. n-1} of size 1 .. m, smallest first.
std::vector<std::vector<std::size_t>> subsets(std::size_t n, std::size_t m)
{
  std::vector<std::vector<std::size_t>> out;
  for (unsigned mask = 1; mask < (1u << n); ++mask)
  {
    std::vector<std::size_t> s;
    for (std::size_t k = 0; k < n; ++k)
      if (mask & (1u << k))
        s.push_back(k);
    if (s.size() <= m)
      out.push_back(s);
  }
  return out;
}
} // namespace

FeatureChoice choose_features(const Matrix& A, const Matrix& B, const std::vector<double>& r,
                              const std::vector<std::vector<std::size_t>>& rows, std::size_t max_features)
{
  if (rows.size() < 2 || A.empty() || A[0].empty() || A[0].size() > 16)
    throw std::logic_error("choose_features: needs two postures and 1 to 16 feature columns");
  const std::size_t ka = A[0].size(), kb = B.empty() ? 0 : B[0].size();
  std::vector<Part> parts;
  for (const auto& pr : rows)
    parts.push_back(part_of(A, B, r, pr));
  std::vector<std::size_t> base; // the free parameters' columns
  for (std::size_t j = 0; j < kb; ++j)
    base.push_back(ka + j);
  FeatureChoice best;
  best.total_gain = 0; // a subset must gain on the held-out postures
  const std::vector<char> all(parts.size(), 1);
  for (const auto& S : subsets(ka, max_features))
  {
    std::vector<std::size_t> idx = S;
    idx.insert(idx.end(), base.begin(), base.end());
    const auto x = fit_on(parts, all, idx);
    bool negative = false;
    for (std::size_t j = 0; j < S.size(); ++j)
      negative = negative || x[j] < 0;
    if (negative)
    {
      best.tried.emplace_back(S, std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    std::vector<double> gains;
    double total = 0;
    for (std::size_t p = 0; p < parts.size(); ++p)
    {
      std::vector<char> use = all;
      use[p] = 0;
      const double with = chi2_at(parts[p], idx, fit_on(parts, use, idx));
      const double without = chi2_at(parts[p], base, fit_on(parts, use, base));
      gains.push_back(without - with);
      total += gains.back();
    }
    best.tried.emplace_back(S, total);
    if (total > best.total_gain)
    {
      best.features = S;
      best.total_gain = total;
      best.held_out_gain = gains;
      best.b.assign(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(S.size()));
      best.d.assign(x.begin() + static_cast<std::ptrdiff_t>(S.size()), x.end());
    }
  }
  return best;
}
} // namespace breastsim::diagnosis
