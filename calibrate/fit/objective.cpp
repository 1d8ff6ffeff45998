// SPDX-License-Identifier: LGPL-3.0-or-later
#include "objective.hpp"
#include "misfit.hpp"
#include <cmath>
#include <limits>

namespace breastsim::calibration
{
Objective::Objective(Config base, const Measurements& data, std::vector<FitParameter> fit,
                     ForwardModel& forward, int evaluations_done)
    : _base(std::move(base)), _data(data), _fit(std::move(fit)), _forward(forward),
      _evaluations(evaluations_done), _best_chi2(std::numeric_limits<double>::infinity())
{
}

void Objective::set_best(const std::vector<double>& y, double chi2)
{
  _best_y = y;
  _best_chi2 = chi2;
}

void Objective::set_correction(std::vector<double> d)
{
  _correction = std::move(d);
  _last_y.clear();
  _last_J = {};
  _best_y.clear();
  _best_chi2 = std::numeric_limits<double>::infinity();
}

std::vector<double> Objective::solve(const std::vector<double>& y, std::vector<Observables>& obs)
{
  obs = _forward.solve(with_parameters(_base, _fit, y));
  std::vector<double> r = weighted_residuals(_data, obs);
  for (std::size_t i = 0; i < _correction.size(); ++i)
    r[i] += _correction[i] / _data.items[i].sigma; // r_i = (G_i + d_i - G_obs,i) / sigma_i
  return r;
}

void Objective::record(const std::vector<double>& y, const std::vector<double>& r)
{
  Evaluation e{++_evaluations, y, calibration::chi2(r), false};
  if (e.chi2 < _best_chi2)
  {
    set_best(y, e.chi2);
    e.best = true;
  }
  if (_callback)
    _callback(e);
}

const std::vector<double>& Objective::residuals(const std::vector<double>& y)
{
  if (!_last_y.empty() && y == _last_y)
    return _last_r;
  // Every group solves the point; all take the first group's r (same decisions on every rank).
  _last_r = _groups ? _groups->replicate([&] { return solve(y, _obs); }) : solve(y, _obs);
  _last_y = y;
  record(y, _last_r);
  return _last_r;
}

double Objective::chi2(const std::vector<double>& y) { return calibration::chi2(residuals(y)); }

std::vector<std::vector<double>> Objective::residuals_at(const std::vector<std::vector<double>>& points)
{
  // The last point stays the caller's (e.g. the Jacobian's base point): a
  // column's solve does not replace it, on any group.
  auto solve_point = [&](std::size_t k)
  {
    std::vector<Observables> obs;
    return solve(points[k], obs);
  };
  std::vector<std::vector<double>> r(points.size());
  if (_groups)
    r = _groups->map(points.size(), solve_point);
  else
    for (std::size_t k = 0; k < points.size(); ++k)
      r[k] = solve_point(k);
  for (std::size_t k = 0; k < points.size(); ++k)
    record(points[k], r[k]);
  return r;
}

Matrix Objective::jacobian(const std::vector<double>& y, double h, bool central)
{
  if (_last_J.y.empty() || _last_J.y != y || _last_J.h != h || _last_J.central != central)
    _last_J = {y, h, central, compute_jacobian(y, h, central)};
  return _last_J.J;
}

Matrix Objective::compute_jacobian(const std::vector<double>& y, double h, bool central)
{
  const std::vector<double> r0 = residuals(y);
  Matrix J(r0.size(), std::vector<double>(y.size()));
  // Exact where the parameter's neighbouring cases share the mesh.
  const Config c = with_parameters(_base, _fit, y);
  std::vector<std::size_t> exact, differenced;
  for (std::size_t j = 0; j < y.size(); ++j)
    (ForwardModel::key_difference(c, _fit[j].key) ? exact : differenced).push_back(j);

  // Exact columns first, while the forward model is at y (the differenced
  // columns' solves move it): dr_i/dy_j = p_j dG_i/dp_j / sigma_i.
  if (!exact.empty())
  {
    std::vector<std::string> keys;
    for (std::size_t j : exact)
      keys.push_back(_fit[j].key);
    auto columns = [&]
    {
      const std::size_t np = _forward.postures().size(), ne = exact.size();
      std::vector<std::vector<Observables>> dG(np); // dG[posture][e]
      for (std::size_t i = 0; i < np; ++i)
        dG[i] = _forward.sensitivities(i, c, keys);
      std::vector<double> flat(r0.size() * ne); // row-major, J restricted to the exact columns
      for (std::size_t e = 0; e < ne; ++e)
      {
        std::vector<Observables> per_posture(np);
        for (std::size_t i = 0; i < np; ++i)
          per_posture[i] = dG[i][e];
        const double p = std::exp(y[exact[e]]);
        for (std::size_t k = 0; k < r0.size(); ++k)
          flat[k * ne + e] = p * model_value(_data.items[k], per_posture) / _data.items[k].sigma;
      }
      return flat;
    };
    // Every group computes them (each keeps its warm starts); all take the first group's.
    const std::vector<double> flat = _groups ? _groups->replicate(columns) : columns();
    for (std::size_t k = 0; k < r0.size(); ++k)
      for (std::size_t e = 0; e < exact.size(); ++e)
        J[k][exact[e]] = flat[k * exact.size() + e];
  }

  // Forward: (r(y + h e_j) - r(y)) / h;  central: (r(y + h e_j) - r(y - h e_j)) / 2h.
  std::vector<std::vector<double>> points;
  for (std::size_t j : differenced)
    for (const double sign : central ? std::vector<double>{1.0, -1.0} : std::vector<double>{1.0})
    {
      points.push_back(y);
      points.back()[j] += sign * h;
    }
  if (points.empty())
    return J;
  const auto r = residuals_at(points);
  const std::size_t per_column = central ? 2 : 1;
  for (std::size_t d = 0; d < differenced.size(); ++d)
  {
    const auto& rp = r[per_column * d];
    const auto& rm = central ? r[per_column * d + 1] : r0;
    for (std::size_t i = 0; i < r0.size(); ++i)
      J[i][differenced[d]] = (rp[i] - rm[i]) / (central ? 2 * h : h);
  }
  return J;
}

std::vector<double> Objective::gradient(const std::vector<double>& y, double h)
{
  const std::vector<double> r = residuals(y);
  const Matrix J = jacobian(y, h);
  std::vector<double> g(y.size(), 0.0);
  for (std::size_t i = 0; i < r.size(); ++i)
    for (std::size_t j = 0; j < y.size(); ++j)
      g[j] += 2 * J[i][j] * r[i];
  return g;
}
} // namespace breastsim::calibration
