#pragma once
// One posture solved from the neutral state: gravity ramped from 0 to 1
// with cut-back, or Newton at full load from the coarse start's guess
// (src/solver/coarse_start.hpp), falling back to the ramp if that fails.
#include "coarse_start.hpp"
#include "config.hpp"
#include "load_stepping.hpp"
#include "observables.hpp"
#include "posture.hpp"

namespace breastsim
{
struct PostureResult
{
  Posture posture;
  Observables observables;
  LoadPathReport path;
  CoarseGuessReport coarse; ///< grid sequencing (src/solver/coarse_start.hpp), if used
  double min_det_F = 0;     ///< smallest det F of the deformed state (element nodes)
  double seconds = 0;
};

/// Solve one posture from the neutral state (u = 0): the gravity load is
/// ramped from 0 to 1 with cut-back. With `coarse` (a coarse model of the
/// same case), Newton first starts at full load from the coarse solution;
/// if that fails, from u = 0 as above. Throws SolveError naming the posture.
PostureResult solve_posture(Model& model, NewtonSolver& newton, const ObservableProbe& probe,
                            const Posture& posture, const Config& c, CoarseStart* coarse = nullptr);
} // namespace breastsim
