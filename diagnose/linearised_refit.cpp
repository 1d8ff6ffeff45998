// SPDX-License-Identifier: LGPL-3.0-or-later
#include "linearised_refit.hpp"
#include "least_squares.hpp"

namespace breastsim::diagnosis
{
std::vector<std::vector<std::size_t>> rows_by_posture(const FitState& s, const Recording& rec)
{
  std::vector<std::vector<std::size_t>> rows(s.distances.size());
  std::size_t j = 0;
  for (std::size_t p = 0; p < s.distances.size(); ++p)
    for (std::size_t i = 0; i < s.distances[p].size(); ++i)
      rows[p].push_back(j++);
  for (std::size_t p = 0; p < rec.postures.size() && p < rows.size(); ++p)
    if (rec.postures[p].nipple)
      for (int k = 0; k < 3; ++k)
        rows[p].push_back(j++);
  return rows;
}

std::vector<char> mask_of(const FitState& s, const std::vector<std::size_t>& rows)
{
  std::vector<char> mask(s.r.size(), 0);
  for (std::size_t i : rows)
    if (i < mask.size())
      mask[i] = 1;
  return mask;
}

std::vector<double> step_without(const FitState& s, const std::vector<char>& held)
{
  const std::size_t n = s.J.empty() ? 0 : s.J[0].size();
  Matrix A(n, std::vector<double>(n, 0.0));
  std::vector<double> b(n, 0.0), delta(n, 0.0);
  for (std::size_t i = 0; i < s.r.size(); ++i)
    if (!held[i])
      for (std::size_t p = 0; p < n; ++p)
      {
        b[p] -= s.J[i][p] * s.r[i];
        for (std::size_t q = 0; q < n; ++q)
          A[p][q] += s.J[i][p] * s.J[i][q];
      }
  if (n > 0 && !calibration::solve_dense(A, b, delta))
    delta.assign(n, 0.0);
  return delta;
}

double predicted_chi2(const FitState& s, const std::vector<char>& held, const std::vector<double>& delta)
{
  const std::size_t n = delta.size();
  double chi2 = 0;
  for (std::size_t i = 0; i < s.r.size(); ++i)
    if (held[i])
    {
      double ri = s.r[i];
      for (std::size_t p = 0; p < n; ++p)
        ri += s.J[i][p] * delta[p];
      chi2 += ri * ri;
    }
  return chi2;
}
} // namespace breastsim::diagnosis
