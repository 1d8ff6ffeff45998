// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Uncertainty of the fitted parameters from the Gauss-Newton approximation
// at the optimum. With J = dr/dy the Jacobian of the weighted residuals in
// log coordinates y = ln p (sigma already in r):
//   Cov(y) = (J^T J)^-1,  SE(y_j) = sqrt(Cov_jj)  (~ relative SE of p_j),
//   95 % interval of p_j = [exp(y_j - 1.96 SE), exp(y_j + 1.96 SE)],
//   corr_jk = Cov_jk / (SE_j SE_k).
// When the misfit exceeds what the stated sigmas allow (reduced chi2 =
// chi2 / (m - n) > 1: model error or optimistic sigmas), Cov is multiplied by
// the reduced chi2 (variance_factor), as in weighted least squares with
// unknown error scale.
#include "objective.hpp"
#include <array>
#include <string>
#include <vector>

namespace breastsim::calibration
{
struct Uncertainty
{
  std::vector<double> se_log;                 ///< SE of ln p (inf: not determined)
  std::vector<std::array<double, 2>> interval; ///< 95 % interval of p
  Matrix correlation;
  std::vector<std::string> flags;             ///< per parameter, "" if fine
  bool singular = false;                      ///< J^T J not invertible
};

/// Parameters correlated beyond this are reported as not separately identifiable.
constexpr double max_correlation = 0.99;
/// SE of ln p beyond this (about 100 % relative error) is reported as undetermined.
constexpr double max_se_log = 0.7;

/// Adds an independent error source of SE `se_extra` (in ln p) to
/// parameter i at value p: SE = hypot(SE, se_extra), the 95 % interval
/// recomputed around p as [p exp(-1.96 SE), p exp(1.96 SE)].
void widen_interval(Uncertainty& u, std::size_t i, double p, double se_extra);

Uncertainty gauss_newton_uncertainty(const Matrix& J, const std::vector<double>& y,
                                     const std::vector<std::string>& names,
                                     double variance_factor = 1.0);
/// Inverse of a symmetric positive definite matrix (Gauss-Jordan with
/// pivoting); returns false if it is singular to working precision.
bool invert_spd(Matrix& A);
} // namespace breastsim::calibration
