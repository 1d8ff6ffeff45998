// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Refits linearised about a fit (FitState's J and r): the Gauss-Newton step
// fitted without a group of residual rows, and the chi2 it predicts for them.
// Shared by the held-out prediction (evidence.hpp) and the jackknife
// estimates of the model-form uncertainty (model_form.hpp).
#include "diagnosis.hpp"
#include <cstddef>
#include <vector>

namespace breastsim::diagnosis
{
/// The residual rows of each posture: its points, then its landmark rows
/// (rows: every posture's points, then each landmark's 3 rows).
std::vector<std::vector<std::size_t>> rows_by_posture(const FitState& s, const Recording& rec);

/// A mask over s.r with the given rows marked.
std::vector<char> mask_of(const FitState& s, const std::vector<std::size_t>& rows);

/// The Gauss-Newton step in ln p fitted on the rows not in `held`:
///   delta = -(J_-g^T J_-g)^-1 J_-g^T r_-g   (zero if singular).
std::vector<double> step_without(const FitState& s, const std::vector<char>& held);

/// |r_g + J_g delta|^2 over the rows marked in `held`.
double predicted_chi2(const FitState& s, const std::vector<char>& held, const std::vector<double>& delta);
} // namespace breastsim::diagnosis
