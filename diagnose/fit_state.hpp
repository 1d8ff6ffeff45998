// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// One fit of a diagnosis: the free parameters (the --fit parameters of the
// current model, plus a candidate's q when it is refitted), bounded
// Levenberg-Marquardt in ln p on the whitened point residuals, and the
// FitState at the optimum (values, Gauss-Newton uncertainty, goodness of fit,
// RMS per posture).
#include "candidates.hpp"
#include "diagnosis.hpp"
#include "point_evaluator.hpp"
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace breastsim::diagnosis
{
/// A free parameter of a fit: p = exp(y) within [lo, hi], written into a case by `set`.
struct Free
{
  std::string name, unit;
  double lo = 0, hi = 0;
  std::function<void(Config&, double)> set;
  double start = 1; ///< starting value [unit]
};

/// The --fit parameters of `list` (e.g. "mu,c") with their bounds around `c`.
std::vector<Free> frees_from_fit(const std::string& list, const Config& c);
/// A candidate's q, within [1e-4, 1e3] x its typical value.
Free free_candidate(const Candidate& cand);
/// `base` with each of `frees` set to exp(y_i).
Config config_at(const Config& base, const std::vector<Free>& frees, const std::vector<double>& y);
/// ln of each free parameter's start, clamped to its bounds.
std::vector<double> start_values(const std::vector<Free>& frees);

/// J = dr/dy of the fit of `frees` of `base` at y, r = ev(config_at(y)).r
/// given: exact (PointEvaluator::jacobian, central residual differences of
/// step 1e-4 in y) for every parameter whose neighbouring cases share the
/// mesh, computed first (the forward model is then at y); forward
/// differences of step `fd_step` for the others (the neutral shape R, H),
/// each one evaluation added to `evaluations`. Throws SolveError.
Matrix fit_jacobian(PointEvaluator& ev, const Config& base, const std::vector<Free>& frees,
                    const std::vector<double>& y, const std::vector<double>& r, double fd_step,
                    int& evaluations);
/// A ridge penalty on the free parameters from `first` on: lambda y_j^2
/// added to chi2 (sqrt(lambda) y_j as extra residual rows), and with
/// `mean_weights` m a zero-mean penalty mean_lambda (sum_j m_j y_j)^2 (one row).
struct Ridge
{
  std::size_t first = 0;
  double lambda = 0;
  std::vector<double> mean_weights;
  double mean_lambda = 0;
};
/// Fit `frees` of `base` from y0; the state at the optimum (no frees: the
/// state of `base`). With a ridge, the fit minimises chi2 + lambda sum y_j^2
/// and the state's chi2, r and J are the data's; its uncertainty is the
/// penalised one, Cov = (J^T J + lambda D)^-1. Throws SolveError.
FitState fit(PointEvaluator& ev, const Config& base, const std::vector<Free>& frees,
             const std::vector<double>& y0, const LsqOptions& o, const std::string& label,
             const Ridge& ridge = {});
/// The fit of `frees` of `base` (e.g. the same model on a finer mesh)
/// from a nearby fit `from` of the same parameters: Gauss-Newton (chord)
/// steps with from's Jacobian,
///   y <- y - (J^T J)^-1 J^T r(y),
/// clamped to the bounds, each kept only if it lowers chi2, at most 3, the
/// first always tried, then until max |step| < 0.02; 2-4 evaluations instead of a Levenberg-Marquardt fit.
/// Its chi2 is evaluated, not predicted. An evaluation that gives none
/// abandons the refit: std::nullopt (the caller starts it again).
using Evaluate = std::function<std::optional<PointEvaluation>(const Config&)>;
std::optional<FitState> gauss_newton_refit(const Evaluate& ev, const Config& base,
                                           const std::vector<Free>& frees, const FitState& from,
                                           const std::string& label);
/// ln of the fitted values of `s`.
std::vector<double> log_values(const FitState& s);
/// The step y + delta within the frees' bounds: y_p + delta_p clamped to
/// [ln lo_p, ln hi_p] (delta may be shorter than y: the rest stays).
std::vector<double> step_within_bounds(std::vector<double> y, const std::vector<double>& delta,
                                       const std::vector<Free>& frees);
/// P(N(0, 1) > z).
double normal_tail(double z);
} // namespace breastsim::diagnosis
