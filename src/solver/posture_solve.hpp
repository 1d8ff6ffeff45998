// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// One posture solved from the neutral state: gravity ramped from 0 to 1
// with cut-back, or Newton at full load from a guess (the coarse start's,
// src/solver/coarse_start.hpp, or any other), falling back to the ramp
// (src/solver/warm_start.hpp).
#include "coarse_start.hpp"
#include <limits>
#include "config.hpp"
#include "load_stepping.hpp"
#include "observables.hpp"
#include "posture.hpp"
#include "warm_start.hpp"

namespace breastsim
{
struct PostureResult
{
  Posture posture;
  Observables observables;
  /// Newton from the guess (if any) and the load ramp: every Newton solve
  /// with its iteration records.
  LoadPathReport path;
  CoarseGuessReport coarse; ///< grid sequencing (src/solver/coarse_start.hpp), if used
  bool converged_from_guess = false; ///< Newton converged from the guess (no ramp)
  double min_det_F = 0;     ///< smallest det F of the deformed state (check points)
  /// Mixed formulation: int p dV / V [Pa]; NaN for the displacement formulation.
  double mean_pressure = std::numeric_limits<double>::quiet_NaN();
  double seconds = 0;
};

/// Solve one posture from the neutral state (u = 0): the gravity load is
/// ramped from 0 to 1 with cut-back. With `coarse` (a coarse model of the
/// same case), Newton first starts at full load from the coarse solution;
/// if that fails, from u = 0 as above. Throws SolveError naming the posture.
PostureResult solve_posture(Model& model, NewtonSolver& newton, const ObservableProbe& probe,
                            const Posture& posture, const Config& c, CoarseStart* coarse = nullptr);

/// The same with any guess at full load (solve_at_full_load; e.g. the last
/// solution of the same posture).
PostureResult solve_posture(Model& model, NewtonSolver& newton, const ObservableProbe& probe,
                            const Posture& posture, const Config& c, const Guess& guess);
} // namespace breastsim
