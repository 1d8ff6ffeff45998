#include "objective.hpp"
#include "misfit.hpp"
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
  _best_y.clear();
  _best_chi2 = std::numeric_limits<double>::infinity();
}

const std::vector<double>& Objective::residuals(const std::vector<double>& y)
{
  if (!_last_y.empty() && y == _last_y)
    return _last_r;
  _obs = _forward.solve(with_parameters(_base, _fit, y));
  _last_r = weighted_residuals(_data, _obs);
  for (std::size_t i = 0; i < _correction.size(); ++i)
    _last_r[i] += _correction[i] / _data.items[i].sigma; // r_i = (G_i + d_i - G_obs,i) / sigma_i
  _last_y = y;
  Evaluation e{++_evaluations, y, calibration::chi2(_last_r), false};
  if (e.chi2 < _best_chi2)
  {
    set_best(y, e.chi2);
    e.best = true;
  }
  if (_callback)
    _callback(e);
  return _last_r;
}

double Objective::chi2(const std::vector<double>& y) { return calibration::chi2(residuals(y)); }

Matrix Objective::jacobian(const std::vector<double>& y, double h, bool central)
{
  const std::vector<double> r0 = residuals(y);
  Matrix J(r0.size(), std::vector<double>(y.size()));
  for (std::size_t j = 0; j < y.size(); ++j)
  {
    // Forward: (r(y + h e_j) - r(y)) / h;  central: (r(y + h e_j) - r(y - h e_j)) / 2h.
    const double hj = h;
    std::vector<double> yp = y;
    yp[j] += hj;
    const std::vector<double> rp = residuals(yp);
    std::vector<double> rm = r0;
    double step = hj;
    if (central)
    {
      std::vector<double> ym = y;
      ym[j] -= hj;
      rm = residuals(ym);
      step = 2 * hj;
    }
    for (std::size_t i = 0; i < r0.size(); ++i)
      J[i][j] = (rp[i] - rm[i]) / step;
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
