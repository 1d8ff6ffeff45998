// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The report of a calibration (report.json, docs/CALIBRATION.md "Outputs"):
// the pieces calibrate() assembles, and what it warns about on the way.
#include "fit_parameters.hpp"
#include "measurements.hpp"
#include "observables.hpp"
#include "uncertainty.hpp"
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace breastsim::calibration
{
/// Warnings of a calibration: logged, and listed in the report.
struct Warnings
{
  nlohmann::json list = nlohmann::json::array();
  void add(const std::string& w);
};

/// "mu = 400 Pa, c = 2e+05 Pa/m" at y = ln p.
std::string parameter_text(const std::vector<FitParameter>& fit, const std::vector<double>& y);

/// Per measurement before/after; `d` is the model-error correction (empty:
/// none), included in model_after.
nlohmann::json misfit_json(const Measurements& data, const std::vector<Observables>& before,
                           const std::vector<Observables>& after, const std::vector<double>& d);

/// Per fitted parameter: initial, fitted, standard error, interval, bounds,
/// at_bound, flag (flags also added to `warnings`).
nlohmann::json fit_json(const std::vector<FitParameter>& fit, const std::vector<double>& y_initial,
                        const std::vector<double>& y, const Uncertainty& u, Warnings& warnings);
} // namespace breastsim::calibration
