// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Missing-physics diagnosis (docs/DIAGNOSE.md). Given a 3D surface
// recording and the user's current model:
//  1. fit the current model (bounded Levenberg-Marquardt in ln p) to the
//     normal distances of the recorded points to the simulated skin, and the
//     nipple landmarks, whitened by the recording's noise sigma;
//  2. test the global fit (chi2 against its degrees of freedom) and locate
//     regions of systematic residual (neighbourhood means, clusters);
//  3. score every candidate of the library (candidates.hpp) by the
//     Lagrange-multiplier (score) statistic at its null value q = 0,
//        U = -j^T P r,  I = j^T P j,  S = U^2 / I  (one-sided: U > 0),
//     with j = dr/dq by a finite difference of warm-started solves and
//     P = I - J (J^T J)^-1 J^T projecting out the already-fitted directions;
//  4. refit with the best-scoring significant candidates switched on and
//     accept the best only if the likelihood ratio LR = chi2_0 - chi2_1
//     exceeds the boundary-corrected critical value (q >= 0: LR ~ 0.5 chi2_0
//     + 0.5 chi2_1 under the null), Bonferroni-corrected over the candidates
//     tested, 0.5 P(chi2_1 > x) = alpha / K, plus the LR the diagnosis
//     mesh's own discretisation error could give that candidate;
//  5. repeat until no candidate is significant.
// Files: diagnose.cpp (the rounds), point_evaluator (the forward map),
// fit_state (one fit), residual_regions (where), candidate_scores (what),
// mesh_error (noise floor, numerical uncertainty), diagnosis_report (text,
// JSON), diagnosis_output (files).
#include "diagnosis.hpp"
#include "diagnosis_report.hpp"
#include <mpi.h>

namespace breastsim::diagnosis
{
/// Collective. Diagnose `rec` against the current model `current`.
Diagnosis diagnose(const Recording& rec, const Config& current, const DiagnoseOptions& o,
                   MPI_Comm comm);
} // namespace breastsim::diagnosis
