// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The calibration objective in log-space coordinates y = ln(p):
//   r(y) = weighted residuals (misfit.hpp),  chi2(y) = |r(y)|^2,
// its Jacobian J = dr/dy (exact sensitivities of the equilibrium for the
// material parameters, forward differences of warm-started solves for the
// shape R, H) and gradient d chi2/dy = 2 J^T r. Counts evaluations,
// keeps the best point and reports progress after each evaluation.
#include "case_groups.hpp"
#include "fit_parameters.hpp"
#include "forward_model.hpp"
#include "measurements.hpp"
#include <functional>
#include <vector>

namespace breastsim::calibration
{
/// Dense m x n matrix, row-major: J[i][j] = d r_i / d y_j.
using Matrix = std::vector<std::vector<double>>;

struct Evaluation
{
  int index = 0;            ///< 1-based evaluation count (including resumed ones)
  std::vector<double> y;
  double chi2 = 0;
  bool best = false;        ///< the best point so far
};

class Objective
{
public:
  Objective(Config base, const Measurements& data, std::vector<FitParameter> fit,
            ForwardModel& forward, int evaluations_done = 0);

  /// Solve the Jacobian's columns over MPI sub-communicators: the forward
  /// model then lives on groups.comm(), and every group evaluates the
  /// points other than the columns itself, the first group's residuals
  /// taken by all (--ranks-per-case).
  void spread_columns(const CaseGroups& groups) { _groups = &groups; }

  /// Called after every new evaluation (progress lines, checkpoint).
  void on_evaluation(std::function<void(const Evaluation&)> f) { _callback = std::move(f); }

  /// Weighted residuals at y (one forward solve of every posture; the last
  /// point is remembered and not solved again).
  const std::vector<double>& residuals(const std::vector<double>& y);
  double chi2(const std::vector<double>& y);
  /// Observables of each posture at the last evaluated point.
  const std::vector<Observables>& observables() const { return _obs; }

  /// J = dr/dy at y = ln p: exact for the material parameters,
  ///   dr_i/dy_j = p_j dG_i/dp_j / sigma_i  (ForwardModel::sensitivities,
  /// one linear solve per parameter and posture, no evaluation counted);
  /// by forward differences with step h in y (central if `central`) for the
  /// neutral shape R, H (the mesh moves), each column one evaluation.
  /// The last Jacobian is remembered: asked again at the same y, h and
  /// `central`, it is not computed again.
  Matrix jacobian(const std::vector<double>& y, double h, bool central = false);
  /// d chi2/dy = 2 J^T r with jacobian(y, h).
  std::vector<double> gradient(const std::vector<double>& y, double h);

  int evaluations() const { return _evaluations; }
  const std::vector<double>& best_y() const { return _best_y; }
  double best_chi2() const { return _best_chi2; }
  /// Model-error correction (approximation-error approach): add `d_i` [m] to
  /// the model value of measurement i,  r_i = (G_i(p) + d_i - G_obs,i) / sigma_i.
  /// Forgets the last point and the best point (chi2 changes meaning).
  void set_correction(std::vector<double> d);
  const std::vector<double>& correction() const { return _correction; }
  /// Start the record of the best point (e.g. from a checkpoint).
  void set_best(const std::vector<double>& y, double chi2);
  const std::vector<FitParameter>& fit() const { return _fit; }
  const Config& base() const { return _base; }

private:
  /// Weighted, corrected residuals of a forward solve at y, and its observables.
  std::vector<double> solve(const std::vector<double>& y, std::vector<Observables>& obs);
  /// Count the evaluation at y, keep the best point, call the callback.
  void record(const std::vector<double>& y, const std::vector<double>& r);
  Matrix compute_jacobian(const std::vector<double>& y, double h, bool central);
  /// r at each point, over the groups (bookkeeping in order on every rank).
  std::vector<std::vector<double>> residuals_at(const std::vector<std::vector<double>>& points);

  const CaseGroups* _groups = nullptr;
  Config _base;
  const Measurements& _data;
  std::vector<FitParameter> _fit;
  ForwardModel& _forward;
  std::function<void(const Evaluation&)> _callback;
  int _evaluations = 0;
  std::vector<double> _last_y, _last_r, _best_y, _correction;
  std::vector<Observables> _obs;
  double _best_chi2 = 0;
  struct LastJacobian
  {
    std::vector<double> y;
    double h = 0;
    bool central = false;
    Matrix J;
  } _last_J;
};
} // namespace breastsim::calibration
