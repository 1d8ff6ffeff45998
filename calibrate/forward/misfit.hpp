// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Weighted misfit between measurements and the model's observables:
//   r_i = (G_i(p) - G_obs,i) / sigma_i,    chi2 = sum_i r_i^2.
#include "measurements.hpp"
#include "observables.hpp"
#include <vector>

namespace breastsim::calibration
{
/// The model value of measurement `m` among the observables of each posture.
double model_value(const Measurement& m, const std::vector<Observables>& per_posture);
/// Weighted residuals r_i (one per measurement).
std::vector<double> weighted_residuals(const Measurements& data,
                                       const std::vector<Observables>& per_posture);
/// chi2 = sum r_i^2.
double chi2(const std::vector<double>& r);
} // namespace breastsim::calibration
