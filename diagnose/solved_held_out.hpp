// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The held-out prediction of each posture solved instead of linearised: the
// model at the parameters fitted without that posture, solved in it. Used
// when the linearised prediction (evidence.hpp held_out_chi2) would refuse a
// term, so that no term is refused on a linearisation outside its range.
#include "diagnosis.hpp"
#include "fit_state.hpp"
#include "point_evaluator.hpp"
#include <optional>
#include <vector>

namespace breastsim::diagnosis
{
/// A fitted model for the held-out prediction: its fit of `frees` of `base`.
struct HeldOutModel
{
  const Config& base;
  const std::vector<Free>& frees;
  const FitState& fit;
};

/// Per posture, the solved held-out chi2; none where it was not solved.
using SolvedChi2 = std::vector<std::optional<double>>;

/// For each posture k of model `m`: the Gauss-Newton step fitted without k's
/// residual rows (linearised_refit.hpp step_without), within the frees'
/// bounds,
///   y_k = ln p + delta_k,
/// the case config_at(base, frees, y_k) solved in posture k alone, and k's
/// chi2 there, sum over its rows of r_i^2 (points, then landmark). None for
/// a posture the evaluator leaves out or whose solve fails. The other
/// postures are left out of these solves only (ev's exclusions are
/// restored, also on an exception). Collective.
SolvedChi2 solved_held_out_chi2(PointEvaluator& ev, const HeldOutModel& m, const Recording& rec);

/// e.held_out_gain solved: per posture, chi2_k without - chi2_k with the
/// term, where both were solved; a posture not solved in either fit keeps
/// its linearised gain (a gain never mixes a solved and a linearised chi2).
/// The linearised gains are kept in e.held_out_gain_linearised.
void set_solved_gains(const SolvedChi2& without, const SolvedChi2& with, Evidence& e);
} // namespace breastsim::diagnosis
