// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Bounded Levenberg-Marquardt for weighted least squares, min |r(y)|^2, with
// the caller's Jacobian J = dr/dy (e.g. exact sensitivities) or forward
// differences (each column one evaluation of r):
//   (J^T J + lambda diag(J^T J)) dy = -J^T r,   y <- clamp(y + dy, lo, hi),
// lambda / 3 after a successful step, x 4 after a rejected one (Marquardt).
// Used by the diagnosis, where each r(y) is a set of warm-started posture
// solves and the residual vector is long (every recorded point).
#include "case_groups.hpp"
#include "objective.hpp"
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace breastsim::calibration
{
using ResidualFunction = std::function<std::vector<double>(const std::vector<double>& y)>;
/// J = dr/dy at y, where r = f(y) is given; adds the evaluations of r it makes.
using JacobianFunction = std::function<Matrix(const std::vector<double>& y,
                                              const std::vector<double>& r, int& evaluations)>;

struct LsqOptions
{
  int max_iterations = 20;
  int max_evaluations = 0; ///< evaluations of r allowed (0: no limit besides the iterations)
  double fd_step = 1e-3;   ///< forward-difference step in y
  double xtol = 1e-3;      ///< stop when max |dy| falls below this
  double ftol_rel = 1e-6;  ///< ... or chi2 decreases less than this, relatively,
  /// provided the Gauss-Newton model at that point predicts at most this
  /// further decrease of chi2 (a short step under heavy damping is not a
  /// minimum: along a curved valley it stops the fit far from one)
  double chi2_tol = 0.1;
  /// The Jacobian's columns over MPI sub-communicators (--ranks-per-case);
  /// null: in turn, on the residual function's communicator.
  const CaseGroups* groups = nullptr;
};

struct LsqResult
{
  std::vector<double> y;
  std::vector<double> r;   ///< residuals at y
  Matrix J;                ///< Jacobian at y
  double chi2 = 0;
  int evaluations = 0;
  int iterations = 0;
  std::string stop_reason;
};

/// Forward-difference Jacobian of f at y (r0 = f(y) given); counts evaluations.
/// With `groups`, column j is solved by the group that runs case j.
Matrix fd_jacobian(const ResidualFunction& f, const std::vector<double>& y,
                   const std::vector<double>& r0, double step, int& evaluations,
                   const CaseGroups* groups = nullptr);

/// Minimise |f(y)|^2 over lo <= y <= hi from y0. `progress(iteration, chi2, y)`
/// is called after every accepted step. The Jacobian is `jacobian`'s, or
/// fd_jacobian's (step o.fd_step) when it is empty; it is always requested
/// at the last point f was evaluated at.
LsqResult levenberg_marquardt(
    const ResidualFunction& f, std::vector<double> y0, const std::vector<double>& lo,
    const std::vector<double>& hi, const LsqOptions& o,
    const std::function<void(int, double, const std::vector<double>&)>& progress = {},
    const JacobianFunction& jacobian = {});

/// The normal equations of J (rows: residuals, n columns) and r:
/// A = J^T J, g = J^T r.
void normal_equations(const Matrix& J, const std::vector<double>& r, std::size_t n, Matrix& A,
                      std::vector<double>& g);

/// The damped Gauss-Newton step dy of the normal equations A = J^T J,
/// g = J^T r:  (A + lambda diag(A)) dy = -g  (lambda = 0: the Gauss-Newton
/// step). None if the matrix is singular to working precision (n = 0: the
/// empty step).
std::optional<std::vector<double>> gauss_newton_step(const Matrix& A, const std::vector<double>& g, double lambda = 0);

/// Solve the small dense system A x = b (Gaussian elimination with partial
/// pivoting); false if A is singular to working precision.
bool solve_dense(Matrix A, std::vector<double> b, std::vector<double>& x);
} // namespace breastsim::calibration
