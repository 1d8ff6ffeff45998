// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Law discovery (docs/DISCOVERY.md): when the model the rounds found still
// misfits the recording and no candidate explains the rest, select
// invariant features of the tissue's energy beyond eq. (5)
// (forms/tissue_law.py: (I1b - 3)^2, (I1b - 3)^3, I2b - 3):
//  1. the exact columns dr/db_k at b = 0 (one linear solve each);
//  2. the subset of at most two features chosen on held-out postures
//     (feature_selection.hpp), coefficients b >= 0;
//  3. the nonlinear fit of its coefficients with the current free parameters;
//  4. accepted if LR exceeds the critical value of chi2 with as many
//     degrees of freedom as features at alpha, every held-out posture but at
//     most one gains, and the surface moves by min_effect x the noise;
//  5. in words: how much the law stiffens in uniaxial stretch, or the
//     second invariant's share of the small-strain shear.
#include "diagnosis.hpp"
#include "feature_selection.hpp"
#include "fit_state.hpp"
#include "point_evaluator.hpp"
#include <string>
#include <vector>

namespace breastsim::diagnosis
{
/// The features of forms/tissue_law.py, in order.
const std::vector<std::string>& law_feature_names();

struct LawDiscovery
{
  bool tried = false;
  bool accepted = false;
  std::vector<std::string> failed;
  std::string skipped;
  FeatureChoice choice;
  std::vector<double> coefficients; ///< b_k [Pa] of every feature (0: not chosen), from the fit
  double lr = 0, critical = 0;
  double effect_rms_mm = 0;
  double mu = 0;                    ///< the fitted tissue mu [Pa]
  /// Uniaxial isochoric stretch and W / W_neo-Hooke there (1: eq. 5).
  std::vector<std::pair<double, double>> stiffening;
  std::string words;
  FitState after;
};

/// Collective. Try the law's features on top of the fit `state` of `frees`.
LawDiscovery discover_law(PointEvaluator& ev, const Recording& rec, const std::vector<Free>& frees,
                          const FitState& state, const DiagnoseOptions& o);
/// W(lambda) / W_neo-Hooke(lambda) in uniaxial isochoric stretch lambda:
/// 1 + sum_k b_k f_k / (mu/2 (I1b - 3)), I1b = lambda^2 + 2/lambda, I2b = 2 lambda + 1/lambda^2.
double law_energy_ratio(const std::vector<double>& b, double mu, double stretch);
/// The law in words (what law_discovery fills in `words`).
std::string law_words(const std::vector<double>& b, double mu);
std::string law_verdict(const LawDiscovery& l, const FitState& before);
std::string law_text(const LawDiscovery& l, const Recording& rec);
nlohmann::json to_json(const LawDiscovery& l);
/// The found law as a term file for forms/ (one registration line):
///   E = int_B q sum_k b_k f_k(F) dV with the b_k as literals.
std::string law_term_source(const LawDiscovery& l, const std::string& name, const std::string& source);
} // namespace breastsim::diagnosis
