// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Sparse selection of features by held-out postures: of the columns A
// (dr/db_k of candidate features, e.g. a tissue law's invariants) every
// subset of at most `max_features` is fitted, linearised and together
// with steps d of the current free parameters (columns B),
//   min_{b_S, d} |r + A_S b_S + B d|^2,
// to all postures but one, and scored by the chi2 it gains on the posture
// left out, summed over the postures; a subset whose fit to every posture
// has a negative coefficient is not in the family (b >= 0) and is skipped.
// The subset with the largest held-out gain wins: the data choose how many
// features, not the fit itself.
#include "diagnosis.hpp"
#include <utility>
#include <vector>

namespace breastsim::diagnosis
{
struct FeatureChoice
{
  std::vector<std::size_t> features;  ///< the chosen columns of A (empty: no subset gains)
  std::vector<double> b, d;           ///< their fit to every posture
  std::vector<double> held_out_gain;  ///< per posture
  double total_gain = 0;
  /// Every subset tried, its total held-out gain (NaN: a negative coefficient).
  std::vector<std::pair<std::vector<std::size_t>, double>> tried;
};

FeatureChoice choose_features(const Matrix& A, const Matrix& B, const std::vector<double>& r,
                              const std::vector<std::vector<std::size_t>>& rows,
                              std::size_t max_features = 2);
} // namespace breastsim::diagnosis
