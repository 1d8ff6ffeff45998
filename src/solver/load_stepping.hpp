// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Continuation in a scalar model parameter (the gravity load factor, a
// suture penalty, ...) with automatic step cut-back.
#include "newton.hpp"
#include "solver_options.hpp"
#include <string>
#include <vector>

namespace breastsim
{
/// One Newton solve on a path: the parameter's value and the solve's report
/// (with its iteration records).
struct PathSolve
{
  double value = 0;
  NewtonReport newton;
};

struct LoadPathReport
{
  int steps = 0;             ///< accepted steps
  int failed_steps = 0;      ///< rejected (cut back) attempts
  int newton_iterations = 0;
  int linear_iterations = 0;
  /// Every Newton solve in order, rejected attempts included.
  std::vector<PathSolve> solves;

  /// Count one Newton solve at `value`: an accepted step if it converged,
  /// else a rejected attempt.
  void add(double value, NewtonReport r);
  /// Add the steps, iterations and solves of a later part of the path.
  void append(LoadPathReport later);
};

/// One parameter of a continuation path: driven from `from` to `to`.
struct ParameterPath
{
  std::string name;
  double from, to;
};

/// Drive model parameter `parameter` from `from` to `to` (fractions s in
/// [0, 1] of the path), re-solving with `newton` at each step. A failed step
/// restores the last converged state and halves the step; below
/// `min_step` a SolveError naming `context` and the fraction is thrown.
/// `reference_norm(s)` gives the force scale for the Newton tolerance.
LoadPathReport continuation(Model& model, NewtonSolver& newton, const std::string& parameter,
                            double from, double to, const LoadStepOptions& options,
                            const std::string& context, double reference_norm);
/// The same with several parameters driven together: each at from + s (to - from).
LoadPathReport continuation(Model& model, NewtonSolver& newton, const std::vector<ParameterPath>& parameters,
                            const LoadStepOptions& options, const std::string& context, double reference_norm);
} // namespace breastsim
