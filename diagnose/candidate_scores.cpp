// SPDX-License-Identifier: LGPL-3.0-or-later
#include "candidate_scores.hpp"
#include "errors.hpp"
#include "fit_state.hpp"
#include "least_squares.hpp"
#include "log.hpp"
#include <cmath>

namespace breastsim::diagnosis
{
double boundary_lr_critical(double level)
{
  // 0.5 P(chi2_1 > x) = 0.5 erfc(sqrt(x / 2)) = level, by bisection.
  double lo = 0, hi = 200;
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(std::sqrt(mid / 2)) > level ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double chi2_critical(double k, double alpha)
{
  double lo = -10, hi = 10; // z with P(N(0, 1) > z) = alpha, by bisection
  for (int i = 0; i < 100; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (normal_tail(mid) > alpha ? lo : hi) = mid;
  }
  const double z = 0.5 * (lo + hi), v = 2 / (9 * k);
  return k * std::pow(1 - v + z * std::sqrt(v), 3); // k (1 - 2/9k + z sqrt(2/9k))^3
}

std::vector<double> project_out(const Matrix& J, const std::vector<double>& j)
{
  const std::size_t n = J.empty() ? 0 : J[0].size();
  if (n == 0)
    return j;
  Matrix A(n, std::vector<double>(n, 0.0));
  std::vector<double> b(n, 0.0), a;
  for (std::size_t i = 0; i < J.size(); ++i)
    for (std::size_t p = 0; p < n; ++p)
    {
      b[p] += J[i][p] * j[i];
      for (std::size_t q = 0; q < n; ++q)
        A[p][q] += J[i][p] * J[i][q];
    }
  if (!calibration::solve_dense(A, b, a))
    return j;
  std::vector<double> out = j;
  for (std::size_t i = 0; i < J.size(); ++i)
    for (std::size_t p = 0; p < n; ++p)
      out[i] -= J[i][p] * a[p];
  return out;
}

namespace
{
double probe_value(const Candidate& c) { return 0.05 * c.typical; }
} // namespace

std::vector<double> probe_residuals(PointEvaluator& ev, const Candidate& c, const FitState& state)
{
  try
  {
    return ev(c.with(state.config, probe_value(c))).r;
  }
  catch (const SolveError& err)
  {
    log::warn("candidate '{}': the probe solve failed ({}); not scored", c.name, err.what());
    return {};
  }
}

CandidateScore score_from_probe(const Candidate& c, const FitState& state,
                                const std::vector<double>& probe_r,
                                const std::vector<double>& mesh_e, double kappa)
{
  CandidateScore s;
  s.name = c.name;
  if (!probe_r.empty())
  {
    const double probe = probe_value(c);
    std::vector<double> j(state.r.size());
    for (std::size_t i = 0; i < j.size(); ++i)
      j[i] = (probe_r[i] - state.r[i]) / probe;
    const auto Pj = project_out(state.J, j);
    double U = 0, I = 0, Ue = 0;
    for (std::size_t i = 0; i < j.size(); ++i)
    {
      U -= Pj[i] * state.r[i];
      I += Pj[i] * Pj[i];
      if (!mesh_e.empty())
        Ue -= Pj[i] * mesh_e[i];
    }
    s.score = (U > 0 && I > 0) ? U * U / I : 0.0;
    s.p_value = I > 0 ? normal_tail(U / std::sqrt(I)) : 1.0;
    s.estimate = I > 0 ? U / I : 0.0;
    // Extrapolated to the error against the exact solution (Richardson,
    // order 1: kappa = 1/(1 - 1/r)).
    s.mesh_allowance = (Ue > 0 && I > 0) ? kappa * kappa * Ue * Ue / I : 0.0;
  }
  log::info("candidate '{}': score {:.1f} (one-sided p = {:.2g}), linearised {} = {:.3g} {}, "
            "mesh-error allowance {:.1f}",
            s.name, s.score, s.p_value, c.parameter, s.estimate, c.unit, s.mesh_allowance);
  return s;
}
} // namespace breastsim::diagnosis
