// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// NLopt driver: minimise chi2(y) over the box of log bounds with an
// algorithm chosen by name. Derivative-free: bobyqa (LN_BOBYQA), sbplx
// (LN_SBPLX), neldermead (LN_NELDERMEAD); gradient-based with the
// Objective's Jacobian (exact sensitivities, forward differences for R, H):
// lbfgs (LD_LBFGS), slsqp (LD_SLSQP), mma (LD_MMA); and lm, bounded
// Levenberg-Marquardt on the weighted residuals (least_squares.hpp).
#include "objective.hpp"
#include <string>
#include <vector>

namespace breastsim::calibration
{
struct OptimizerOptions
{
  std::string algorithm = "lm";
  int max_evals = 200;     ///< objective evaluations allowed (each solves every posture)
  double xtol_log = 1e-3;  ///< stop when every ln p moves less than this (0.1 %)
  double ftol_rel = 1e-8;  ///< ... or chi2 changes less than this, relatively
  double initial_step = 0.2; ///< first step in ln p (derivative-free algorithms)
  double fd_step = 1e-3;   ///< finite-difference step in ln p (gradients, Jacobian)
};

struct OptimizerResult
{
  std::vector<double> y;   ///< best point found
  double chi2 = 0;
  std::string stop_reason; ///< NLopt's result, in words
};

/// Names accepted by --algorithm.
std::vector<std::string> algorithm_names();
/// Throws InputError for an unknown algorithm name.
void check_algorithm(const std::string& name);
bool uses_gradient(const std::string& name);

/// Minimise from y0 (inside the bounds). Exceptions thrown by a forward
/// solve (SolveError) stop the optimiser and are rethrown.
OptimizerResult minimise(Objective& f, const std::vector<double>& y0, const OptimizerOptions& o);
} // namespace breastsim::calibration
