// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Model-form uncertainty of the found values, estimated from the data by
// delete-a-group jackknives of linearised refits (linearised_refit.hpp).
// With G groups of residual rows and delta_g the Gauss-Newton step in ln p
// fitted without group g,
//   se^2 = (G - 1)/G sum_g (delta_g - mean delta)^2,
// which is of the statistical size when every group asks for the same
// values and grows when they disagree: a misshapen or missing term leaves a
// spatially coherent misfit that white-noise intervals do not see.
//   posture jackknife: a group is a posture (its points and landmark);
//   patch jackknife:   a group is a patch of a posture's points, the points
//                      split into b x b patches of equal count along the two
//                      principal axes of the posture's point cloud
//                      (landmark rows stay in every refit).
// The model-form SE is the larger of the two per parameter: the posture
// jackknife sees postures that want other values, the patch jackknife
// regions of one posture that do (and, with 4 postures, is the steadier).
#include "diagnosis.hpp"
#include <vector>

namespace breastsim::diagnosis
{
/// Indices of `points` in b x b patches of equal count: b slabs along the
/// cloud's first principal axis, each split into b along its second
/// (b <= 1 or fewer than 2 b^2 points: one patch of all).
std::vector<std::vector<std::size_t>> principal_patches(const std::vector<Point>& points, int b);

/// The delete-a-group jackknife SE of ln p over the groups of rows `masks`.
std::vector<double> group_jackknife_se(const FitState& s, const std::vector<std::vector<char>>& masks);

/// Groups: the postures.
std::vector<double> posture_jackknife_se(const FitState& s, const Recording& rec);

/// Groups: b x b patches of each posture's points (b <= 0: none, zeros).
std::vector<double> patch_jackknife_se(const FitState& s, const Recording& rec, int b);

/// Both jackknives of `s` and their per-parameter maximum, into d
/// (se_posture_jackknife, se_patch_jackknife, se_model_form).
void estimate_model_form(const FitState& s, const Recording& rec, int b, Diagnosis& d);

/// Add `se_model_form` to each parameter's SE of ln p in quadrature and
/// recompute the 95 % intervals.
void widen_by_model_form(FitState& s, const std::vector<double>& se_model_form);
} // namespace breastsim::diagnosis
