// SPDX-License-Identifier: LGPL-3.0-or-later
#include "fit_state.hpp"
#include "fit_parameters.hpp"
#include "least_squares.hpp"
#include "log.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace breastsim::diagnosis
{
Config config_at(const Config& base, const std::vector<Free>& frees, const std::vector<double>& y)
{
  Config c = base;
  for (std::size_t i = 0; i < frees.size(); ++i)
    frees[i].set(c, std::exp(y[i]));
  c.validate();
  return c;
}

namespace
{

/// RMS and largest |distance| of each posture.
void distance_statistics(FitState& s)
{
  for (const auto& d : s.distances)
  {
    double ss = 0, mx = 0;
    for (double x : d)
    {
      ss += x * x;
      mx = std::max(mx, std::abs(x));
    }
    s.rms.push_back(std::sqrt(ss / std::max<std::size_t>(d.size(), 1)));
    s.max_abs.push_back(mx);
  }
}

/// The ridge's residual rows at y: sqrt(lambda) y_j, then sqrt(mean_lambda) sum_j m_j y_j.
std::vector<double> ridge_rows(const std::vector<double>& y, const Ridge& ridge)
{
  std::vector<double> r;
  for (std::size_t j = ridge.first; ridge.lambda > 0 && j < y.size(); ++j)
    r.push_back(std::sqrt(ridge.lambda) * y[j]);
  if (!ridge.mean_weights.empty())
  {
    double mean = 0;
    for (std::size_t k = 0; k < ridge.mean_weights.size() && ridge.first + k < y.size(); ++k)
      mean += ridge.mean_weights[k] * y[ridge.first + k];
    r.push_back(std::sqrt(ridge.mean_lambda) * mean);
  }
  return r;
}

/// J with the ridge rows' derivatives appended.
Matrix with_ridge_rows(Matrix J, std::size_t columns, const Ridge& ridge)
{
  for (std::size_t j = ridge.first; ridge.lambda > 0 && j < columns; ++j)
  {
    J.emplace_back(columns, 0.0);
    J.back()[j] = std::sqrt(ridge.lambda);
  }
  if (!ridge.mean_weights.empty())
  {
    J.emplace_back(columns, 0.0);
    for (std::size_t k = 0; k < ridge.mean_weights.size() && ridge.first + k < columns; ++k)
      J.back()[ridge.first + k] = std::sqrt(ridge.mean_lambda) * ridge.mean_weights[k];
  }
  return J;
}

FitState make_state(const Config& c, const std::vector<Free>& frees,
                    const std::vector<double>& y, const Matrix& J, const PointEvaluation& e,
                    int evaluations, const Ridge& ridge = {})
{
  FitState s;
  s.config = c;
  s.distances = e.distances;
  s.nipple_error = e.nipple_error;
  s.r = e.r;
  s.J = J;
  s.evaluations = evaluations;
  for (double x : e.r)
    s.chi2 += x * x;
  s.dof = static_cast<int>(e.r.size()) - static_cast<int>(frees.size());
  s.gof_z = (s.chi2 - s.dof) / std::sqrt(2.0 * s.dof);
  s.gof_p = normal_tail(s.gof_z);
  for (std::size_t i = 0; i < frees.size(); ++i)
  {
    s.names.push_back(frees[i].name);
    s.units.push_back(frees[i].unit);
    s.values.push_back(std::exp(y[i]));
  }
  if (!frees.empty())
    s.uncertainty = calibration::gauss_newton_uncertainty(with_ridge_rows(J, frees.size(), ridge), y,
                                                          s.names,
                                                          std::max(1.0, s.chi2 / std::max(s.dof, 1)));
  distance_statistics(s);
  return s;
}

/// `base` with each of `frees` set to exp(y_i), not validated (a
/// differentiation step may pass a bound by a hair).
Config config_near(const Config& base, const std::vector<Free>& frees, const std::vector<double>& y)
{
  Config c = base;
  for (std::size_t i = 0; i < frees.size(); ++i)
    frees[i].set(c, std::exp(y[i]));
  return c;
}
} // namespace

Matrix fit_jacobian(PointEvaluator& ev, const Config& base, const std::vector<Free>& frees,
                    const std::vector<double>& y, const std::vector<double>& r, double fd_step,
                    int& evaluations)
{
  constexpr double h = 1e-4;
  const Config c = config_at(base, frees, y);
  std::vector<ForwardModel::CaseDifference> directions;
  std::vector<std::size_t> exact, differenced;
  for (std::size_t j = 0; j < y.size(); ++j)
  {
    auto yp = y, ym = y;
    yp[j] += h;
    ym[j] -= h;
    ForwardModel::CaseDifference d{config_near(base, frees, yp), config_near(base, frees, ym), 2 * h};
    if (ForwardModel::same_mesh(c, d.plus) && ForwardModel::same_mesh(c, d.minus))
    {
      exact.push_back(j);
      directions.push_back(std::move(d));
    }
    else
      differenced.push_back(j);
  }
  Matrix J(r.size(), std::vector<double>(y.size(), 0.0));
  if (!directions.empty()) // first, while the forward model is at y
  {
    const auto Je = ev.jacobian(c, directions);
    for (std::size_t i = 0; i < r.size(); ++i)
      for (std::size_t e = 0; e < exact.size(); ++e)
        J[i][exact[e]] = Je[i][e];
  }
  for (std::size_t j : differenced) // J_ij = (r_i(y + h e_j) - r_i(y)) / h
  {
    auto yp = y;
    yp[j] += fd_step;
    const auto rp = ev(config_at(base, frees, yp)).r;
    ++evaluations;
    for (std::size_t i = 0; i < r.size(); ++i)
      J[i][j] = (rp[i] - r[i]) / fd_step;
  }
  return J;
}

double normal_tail(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }

std::vector<Free> frees_from_fit(const std::string& list, const Config& c)
{
  std::vector<Free> out;
  if (list.empty())
    return out;
  for (const auto& p : calibration::parse_fit(list, c))
  {
    const std::string key = p.key;
    out.push_back({p.name, p.unit, p.lower, p.upper, [key](Config& c, double v) { c.set(key, v); },
                   c.number(key)});
  }
  return out;
}

Free free_candidate(const Candidate& cand)
{
  return {cand.parameter, cand.unit, cand.typical * 1e-4, cand.typical * 1e3,
          [&cand](Config& c, double v) { c = cand.with(c, v); }, cand.typical};
}

std::vector<double> start_values(const std::vector<Free>& frees)
{
  std::vector<double> y0;
  for (const auto& f : frees)
    y0.push_back(std::log(std::clamp(f.start, f.lo, f.hi)));
  return y0;
}

FitState fit(PointEvaluator& ev, const Config& base, const std::vector<Free>& frees,
             const std::vector<double>& y0, const LsqOptions& o, const std::string& label,
             const Ridge& ridge)
{
  if (frees.empty())
  {
    const PointEvaluation e = ev(base);
    return make_state(base, frees, {}, {}, e, 1);
  }
  std::vector<double> lo, hi;
  for (const auto& f : frees)
  {
    lo.push_back(std::log(f.lo));
    hi.push_back(std::log(f.hi));
  }
  std::size_t data_rows = 0;
  auto f = [&](const std::vector<double>& y) // r, then the ridge's rows
  {
    auto r = ev(config_at(base, frees, y)).r;
    data_rows = r.size();
    const auto extra = ridge_rows(y, ridge);
    r.insert(r.end(), extra.begin(), extra.end());
    return r;
  };
  auto progress = [&](int it, double chi2, const std::vector<double>& y)
  {
    std::string p;
    for (std::size_t i = 0; i < y.size(); ++i)
      p += fmt::format("{}{} = {:.4g}", i ? ", " : "", frees[i].name, std::exp(y[i]));
    log::info("{}: iteration {}, chi2 = {:.1f}, {}", label, it, chi2, p);
  };
  auto jacobian = [&](const std::vector<double>& y, const std::vector<double>& r, int& evaluations)
  {
    const std::vector<double> data(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(data_rows));
    return with_ridge_rows(fit_jacobian(ev, base, frees, y, data, o.fd_step, evaluations), y.size(),
                           ridge);
  };
  const calibration::LsqResult r =
      calibration::levenberg_marquardt(f, y0, lo, hi, o, progress, jacobian);
  log::info("{}: {} ({} evaluations)", label, r.stop_reason, r.evaluations);
  const Config c = config_at(base, frees, r.y);
  const PointEvaluation e = ev(c);
  const Matrix J_data(r.J.begin(), r.J.begin() + static_cast<std::ptrdiff_t>(e.r.size()));
  return make_state(c, frees, r.y, J_data, e, r.evaluations + 1, ridge);
}

std::optional<FitState> gauss_newton_refit(const Evaluate& ev, const Config& base,
                                           const std::vector<Free>& frees, const FitState& from,
                                           const std::string& label)
{
  constexpr int max_steps = 3;       // chord steps with from's Jacobian
  constexpr double step_tol = 0.02;  // stop when max |delta ln p| falls below this
  std::vector<double> y = log_values(from);
  const Config c0 = config_at(base, frees, y);
  const auto e0 = ev(c0);
  if (!e0)
    return std::nullopt;
  FitState best = make_state(c0, frees, y, from.J, *e0, 1);
  const double chi2_start = best.chi2;
  const std::size_t n = y.size();
  for (int k = 0; k < max_steps && n > 0 && from.J.size() == best.r.size(); ++k)
  {
    Matrix A;
    std::vector<double> g;
    calibration::normal_equations(from.J, best.r, n, A, g);
    const auto delta = calibration::gauss_newton_step(A, g); // -(J^T J)^-1 J^T r
    if (!delta)
      break; // singular: no step
    y = step_within_bounds(log_values(best), *delta, frees);
    double largest = 0;
    for (double d : *delta)
      largest = std::max(largest, std::abs(d));
    if (k > 0 && largest < step_tol)
      break; // the first step is always tried: it measures how far the optimum moved
    const Config c = config_at(base, frees, y);
    const auto e = ev(c);
    if (!e)
      return std::nullopt;
    FitState next = make_state(c, frees, y, from.J, *e, best.evaluations + 1);
    if (!(next.chi2 < best.chi2))
      break;
    best = std::move(next);
  }
  log::info("{}: Gauss-Newton steps from the nearby fit, chi2 {:.1f} -> {:.1f}", label, chi2_start,
            best.chi2);
  return best;
}

std::vector<double> log_values(const FitState& s)
{
  std::vector<double> y;
  for (double v : s.values)
    y.push_back(std::log(v));
  return y;
}

std::vector<double> step_within_bounds(std::vector<double> y, const std::vector<double>& delta,
                                       const std::vector<Free>& frees)
{
  // y_p <- clamp(y_p + delta_p, ln lo_p, ln hi_p)
  for (std::size_t p = 0; p < y.size() && p < delta.size() && p < frees.size(); ++p)
    y[p] = std::clamp(y[p] + delta[p], std::log(frees[p].lo), std::log(frees[p].hi));
  return y;
}
} // namespace breastsim::diagnosis
