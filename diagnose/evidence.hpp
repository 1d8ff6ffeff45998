// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The evidence for and against adding a refitted candidate (diagnose.hpp):
// beyond the likelihood ratio, its effect on the surface in mm, how far its
// interval reaches towards the null, whether it predicts postures it was not
// fitted on, and whether its likelihood ratio survives mesh refinement.
#include "diagnosis.hpp"
#include <optional>
#include <string>
#include <vector>

namespace breastsim::diagnosis
{
/// The effect of a term in mm: the change of the model surface (normal
/// distances at the recorded points) between the fit without and with it.
/// Per posture RMS and max, and RMS over all points (the one the
/// practical-significance rule judges).
void effect_size(const FitState& without, const FitState& with, Evidence& e);
/// The refinement check's rule: LR_f and LR_0 both above their critical values.
bool survives_refinement(const Evidence& e);

/// The part of the effect that the 95 % interval cannot tell from the null:
/// effect x q_lo / q_hat (the effect is linear in q for small q; q = 0 is the
/// model without the term).
double effect_at_interval_edge(const FitState& with, const std::string& parameter, double effect);

/// Held-out prediction, linearised about the fit: for each posture k, the
/// Gauss-Newton step fitted without k's residuals,
///   delta_k = -(J_-k^T J_-k)^-1 J_-k^T r_-k,
/// and the chi2 of posture k predicted with it, |r_k + J_k delta_k|^2.
/// (Residual rows: each posture's points, then each landmark's 3 rows.)
std::vector<double> held_out_chi2(const FitState& s, const Recording& rec);

/// The likelihood ratio extrapolated to the continuum from the diagnosis mesh
/// h and the mesh h/r: the square root of the LR (the effect in noise units)
/// extrapolated as an error of order p,
///   sqrt(LR_0) = sqrt(LR_f) + (sqrt(LR_f) - sqrt(LR_h)) / (r^p - 1).
double continuum_lr(double lr_h, double lr_fine, double ratio, double order);

/// The refinement check's critical value, on the finer mesh and in the
/// continuum alike: the statistical critical value c plus the diagnosis
/// mesh's allowance A (the LR its error could give), c + A.
double refinement_critical(double statistical, double allowance);

/// The held-out rule (DiagnoseOptions::held_out_check): why it refuses `e`
/// (its summed held-out chi2 gain is not positive, or no more than half of
/// the postures gain), or none.
std::optional<std::string> held_out_refusal(const Evidence& e, const DiagnoseOptions& o);

/// The acceptance rules in force (DiagnoseOptions) applied to `e`: fills
/// e.failed with a plain-words reason per failed rule.
void judge(Evidence& e, const DiagnoseOptions& o, double noise_sigma);

/// The evidence as plain text lines (diagnosis.txt) and JSON.
std::string evidence_text(const Evidence& e);
nlohmann::json to_json(const Evidence& e);
} // namespace breastsim::diagnosis
