// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The one fallback of every solve at full load: start from a guess (the
// coarse start's interpolant, the level below, the last solution of a
// calibration), use it only if it inverts no element and its energy is
// below that of u = 0, run Newton from it, and if any of this fails ramp
// the load from u = 0.
#include "load_stepping.hpp"
#include <functional>
#include <string>

namespace breastsim
{
/// A starting guess at full load.
struct Guess
{
  /// Sets the model's displacement to the guess (parameters as they are);
  /// returns false, with the reason, when there is none. Collective.
  std::function<bool(Model& model, std::string& reason)> set;
  std::string name = "the guess"; ///< in messages ("Newton from <name> failed")
  bool quiet = false;             ///< fallbacks logged at debug level, not info
};

struct WarmStartReport
{
  bool used = false;      ///< the guess was admissible and Newton started from it
  bool converged = false; ///< Newton converged from the guess (no ramp)
  std::string reason;     ///< why the guess was not used, or why Newton failed from it
  /// Newton from the guess (one step at load 1) and the ramp (if any).
  LoadPathReport path;
};

/// Why the model's current displacement is not an admissible start: it
/// inverts an element (min det F <= 0) or its energy is not below
/// `energy_at_rest`, the energy of u = 0. Empty when admissible. Collective.
std::string inadmissible_guess(Model& model, double energy_at_rest);

/// Solve `model` at load 1 (model parameter "load"): from `guess` if it has
/// one and it is admissible (inadmissible_guess), by Newton; otherwise, or
/// if Newton fails from it, from u = 0 with the load ramped from 0 to 1
/// (`ramp`, continuation). `context` names the solve in messages and in the
/// SolveError thrown when the ramp fails; `reference_norm` is the force
/// scale of the Newton tolerance.
WarmStartReport solve_at_full_load(Model& model, NewtonSolver& newton, const Guess& guess,
                                   const LoadStepOptions& ramp, const std::string& context,
                                   double reference_norm);
} // namespace breastsim
