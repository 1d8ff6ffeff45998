// SPDX-License-Identifier: LGPL-3.0-or-later
#include "misfit.hpp"

namespace breastsim::calibration
{
double model_value(const Measurement& m, const std::vector<Observables>& per_posture)
{
  const Observables& o = per_posture.at(m.posture);
  switch (m.quantity)
  {
  case Quantity::projection: return o.projection;
  case Quantity::z_min: return o.z_min;
  case Quantity::z_max: return o.z_max;
  case Quantity::height: return o.z_max - o.z_min;
  case Quantity::nipple_x: return o.nipple[0];
  case Quantity::nipple_y: return o.nipple[1];
  case Quantity::nipple_z: return o.nipple[2];
  case Quantity::base_perimeter: return o.base_perimeter;
  }
  return 0;
}

std::vector<double> weighted_residuals(const Measurements& data,
                                       const std::vector<Observables>& per_posture)
{
  std::vector<double> r;
  for (const auto& m : data.items)
    r.push_back((model_value(m, per_posture) - m.value) / m.sigma);
  return r;
}

double chi2(const std::vector<double>& r)
{
  double s = 0;
  for (double x : r)
    s += x * x;
  return s;
}
} // namespace breastsim::calibration
