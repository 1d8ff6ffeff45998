// SPDX-License-Identifier: LGPL-3.0-or-later
#include "calibration_report.hpp"
#include "log.hpp"
#include "misfit.hpp"
#include <cmath>
#include <fmt/format.h>

namespace breastsim::calibration
{
void Warnings::add(const std::string& w)
{
  list.push_back(w);
  log::warn("{}", w);
}

std::string parameter_text(const std::vector<FitParameter>& fit, const std::vector<double>& y)
{
  std::string s;
  for (std::size_t j = 0; j < fit.size(); ++j)
    s += fmt::format("{}{} = {:.5g} {}", j ? ", " : "", fit[j].name, std::exp(y[j]), fit[j].unit);
  return s;
}

nlohmann::json misfit_json(const Measurements& data, const std::vector<Observables>& before,
                           const std::vector<Observables>& after, const std::vector<double>& d)
{
  auto rows = nlohmann::json::array();
  for (std::size_t i = 0; i < data.items.size(); ++i)
  {
    const auto& m = data.items[i];
    const double di = d.empty() ? 0.0 : d[i];
    const double b = model_value(m, before), a = model_value(m, after) + di;
    rows.push_back({{"measurement", m.label},
                    {"measured", m.value},
                    {"sigma", m.sigma},
                    {"model_before", b},
                    {"model_after", a},
                    {"model_error_correction", di},
                    {"weighted_residual_before", (b - m.value) / m.sigma},
                    {"weighted_residual_after", (a - m.value) / m.sigma}});
  }
  return rows;
}

nlohmann::json fit_json(const std::vector<FitParameter>& fit, const std::vector<double>& y_initial,
                        const std::vector<double>& y, const Uncertainty& u, Warnings& warnings)
{
  auto rows = nlohmann::json::array();
  for (std::size_t j = 0; j < fit.size(); ++j)
  {
    const double p = std::exp(y[j]);
    rows.push_back({{"name", fit[j].name},
                    {"key", fit[j].key},
                    {"unit", fit[j].unit},
                    {"initial", std::exp(y_initial[j])},
                    {"fitted", p},
                    {"standard_error", p * u.se_log[j]},
                    {"relative_standard_error", u.se_log[j]},
                    {"interval_95", {u.interval[j][0], u.interval[j][1]}},
                    {"bounds", {fit[j].lower, fit[j].upper}},
                    {"at_bound", p <= fit[j].lower * (1 + 1e-6) || p >= fit[j].upper * (1 - 1e-6)},
                    {"flag", u.flags[j]}});
    if (!u.flags[j].empty())
      warnings.add(fit[j].name + ": " + u.flags[j]);
  }
  return rows;
}

} // namespace breastsim::calibration
