// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The linearised, ridge-penalised fit of a field's amplitudes a (the
// columns A = dr/da) together with steps d of the current model's free
// parameters (the columns B = dr/dy), at the current fit's residuals r:
//   min_{a, d} |r + A a + B d|^2 + lambda |a|^2,
// with lambda chosen on held-out postures: each posture in turn is
// predicted by the fit to the others, and lambda maximises the sum of the
// held-out chi2 gains over the same fit without the field (a = 0). With
// weights m (the basis functions' volume means) the field keeps a zero
// mean, m . a = 0 (a penalty 1e6 s (m . a)^2): a uniform stiffening is the
// fitted mu's, not the field's.
#include "diagnosis.hpp"
#include <utility>
#include <vector>

namespace breastsim::diagnosis
{
struct RidgeChoice
{
  double lambda = 0;                 ///< chosen penalty
  double scale = 0;                  ///< s = tr(A^T A) / columns
  std::vector<double> a, d;          ///< its fit to every posture
  std::vector<double> held_out_gain; ///< per posture: chi2 without - with the field, held out
  double total_gain = 0;             ///< their sum (the criterion)
  double dof = 0;                    ///< effective parameters of the field: tr((G + lambda D)^-1 G) - dim d
  std::vector<std::pair<double, double>> path; ///< (lambda, total held-out gain) of every lambda tried
};

/// Tries lambda = s 10^(j/2), j = -6 .. 8, s = tr(A^T A) / columns of A.
/// rows: the rows of each posture (rows_by_posture). At least two postures.
RidgeChoice choose_ridge(const Matrix& A, const Matrix& B, const std::vector<double>& r,
                         const std::vector<std::vector<std::size_t>>& rows,
                         const std::vector<double>& mean_weights = {});
/// The weight of the zero-mean penalty relative to s = tr(A^T A) / columns.
constexpr double zero_mean_weight = 1e6;
} // namespace breastsim::diagnosis
