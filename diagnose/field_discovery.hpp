// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Field discovery (docs/DIAGNOSE.md): when the model the rounds found
// still misfits the recording (goodness of fit p < alpha) and no candidate
// explains the rest, fit a smooth stiffness field of the tissue,
//   stiffness exp(s(X)) x tissue,  s(X) = sum_k a_k exp(-|X - c_k|^2 / (2 w^2))
// (forms/tissue_field.py), on a lattice of centres inside the cap:
//  1. the exact columns dr/da_k at a = 0 (one linear solve each);
//  2. the ridge penalty lambda |a|^2 chosen on held-out postures, with the
//     field's volume mean held at zero so that mu carries the bulk
//     stiffness (field_ridge.hpp);
//  3. the nonlinear fit of a with the current free parameters, penalised;
//  4. accepted if its LR = chi2_before - chi2_after exceeds the critical
//     value of chi2 with the field's effective parameters at alpha, every
//     held-out posture but at most one gains, and it changes the surface by
//     at least min_effect x the noise (RMS);
//  5. interpreted in words (field_summary.hpp).
#include "diagnosis.hpp"
#include "field_basis.hpp"
#include "field_ridge.hpp"
#include "field_summary.hpp"
#include "fit_state.hpp"
#include "point_evaluator.hpp"
#include <string>
#include <vector>

namespace breastsim::diagnosis
{
struct FieldDiscovery
{
  bool tried = false;
  bool accepted = false;
  std::vector<std::string> failed; ///< the rules it fails (accepted: none)
  std::string skipped;             ///< why it was not tried ("" if tried)
  FieldBasis basis;
  std::vector<double> amplitudes;  ///< a_k of the penalised fit
  Matrix amplitude_cov;            ///< their covariance (penalised Gauss-Newton)
  RidgeChoice ridge;
  double lr = 0, critical = 0;
  double effect_rms_mm = 0;        ///< RMS change of the surface over all points
  FieldSummary summary;
  FitState after;                  ///< the model with the field
};

/// Collective. Try a field on top of the fit `state` of `frees` of the
/// current model.
FieldDiscovery discover_field(PointEvaluator& ev, const Recording& rec,
                              const std::vector<Free>& frees, const FitState& state,
                              const DiagnoseOptions& o);
/// The verdict's sentence on the field ("" if not tried), against the fit
/// `before` it.
std::string field_verdict(const FieldDiscovery& f, const FitState& before);
/// The field's lines of the report.
std::string field_text(const FieldDiscovery& f, const Recording& rec);
nlohmann::json to_json(const FieldDiscovery& f);
} // namespace breastsim::diagnosis
