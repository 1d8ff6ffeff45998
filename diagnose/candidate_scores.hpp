// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The WHAT step of a diagnosis: the score (Lagrange-multiplier) statistic of
// a candidate at its null value q = 0 (diagnose.hpp, step 3), and the
// critical value of the likelihood-ratio test of its refit.
#include "candidates.hpp"
#include "diagnosis.hpp"
#include "point_evaluator.hpp"
#include <vector>

namespace breastsim::diagnosis
{
/// Critical value x of the boundary-corrected LR test: 0.5 P(chi2_1 > x) = level.
double boundary_lr_critical(double level);

/// x with P(chi2_k > x) = alpha (Wilson-Hilferty; k >= 1).
double chi2_critical(double k, double alpha);

/// Projected sensitivity P j with P = I - J (J^T J)^-1 J^T.
std::vector<double> project_out(const Matrix& J, const std::vector<double>& j);

/// The residuals of the probe solve of candidate `c` at q = 0.05 q_typical
/// (empty if the solve failed): the one solve of a candidate's score.
std::vector<double> probe_residuals(PointEvaluator& ev, const Candidate& c, const FitState& state);
/// Score of candidate `c` at q = 0 against the fit `state`: j = dr/dq by a
/// forward difference at q = 0.05 q_typical, U = -j^T P r, I = j^T P j,
/// S = U^2 / I (one-sided), with the LR the mesh error `mesh_e`
/// (e = r_h - r_{h/r}; empty: none) would give it, extrapolated by kappa.
/// An empty `probe_r` (failed probe solve) leaves it unscored (S = 0, p = 1).
CandidateScore score_from_probe(const Candidate& c, const FitState& state,
                                const std::vector<double>& probe_r,
                                const std::vector<double>& mesh_e, double kappa);
} // namespace breastsim::diagnosis
