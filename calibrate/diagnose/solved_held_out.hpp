#pragma once
// The held-out prediction of each posture solved instead of linearised: the
// model at the parameters fitted without that posture, solved in it. Used
// when the linearised prediction (evidence.hpp held_out_chi2) would refuse a
// term, so that no term is refused on a linearisation outside its range.
#include "diagnosis.hpp"
#include "fit_state.hpp"
#include "point_evaluator.hpp"
#include <vector>

namespace breastsim::calibration
{
/// For each posture k of fit `s` (of `frees` of `base`): the Gauss-Newton
/// step fitted without k's residual rows (linearised_refit.hpp step_without),
///   y_k = ln p + delta_k,
/// the case config_at(base, frees, y_k) solved in posture k alone, and k's
/// chi2 there, sum over its rows of r_i^2 (points, then landmark). A posture
/// whose solve fails keeps `linearised[k]`. The other postures are left out
/// of these solves only (ev's exclusions are restored). Collective.
std::vector<double> solved_held_out_chi2(PointEvaluator& ev, const Config& base,
                                         const std::vector<Free>& frees, const FitState& s,
                                         const Recording& rec, const std::vector<double>& linearised);

/// A fitted model for the held-out prediction: its fit of `frees` of `base`.
struct HeldOutModel
{
  const Config& base;
  const std::vector<Free>& frees;
  const FitState& fit;
};

/// e.held_out_gain solved: chi2_k of `without` - chi2_k of `with`, each
/// solved_held_out_chi2; the linearised gains are kept in
/// e.held_out_gain_linearised. Collective.
void solve_held_out_gains(PointEvaluator& ev, const HeldOutModel& without, const HeldOutModel& with,
                          const Recording& rec, Evidence& e);
} // namespace breastsim::calibration
