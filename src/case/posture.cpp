// SPDX-License-Identifier: LGPL-3.0-or-later
#include "posture.hpp"
#include "case_options.hpp"
#include "errors.hpp"
#include <cmath>
#include <fmt/format.h>
#include <map>

namespace breastsim
{
Posture named_posture(const std::string& name)
{
  static const std::map<std::string, double> angles
      = {{"standing", 0.0}, {"supine", 90.0}, {"all_fours", -90.0}, {"prone", -90.0}};
  auto it = angles.find(name);
  if (it == angles.end())
    throw InputError(fmt::format("unknown posture '{}' (allowed: standing, supine, all_fours, prone)", name));
  return {name, it->second};
}

Posture posture_from_angle(double theta_deg)
{
  if (!(theta_deg >= -180 && theta_deg <= 180))
    throw InputError(fmt::format("posture angle theta = {} deg is out of range [-180, 180]", theta_deg));
  return {fmt::format("theta_{:g}", theta_deg), theta_deg};
}

std::array<double, 3> gravity_vector(double theta_deg, double g)
{
  const double t = theta_deg * M_PI / 180.0;
  return {0.0, -g * std::sin(t), -g * std::cos(t)};
}

std::vector<Posture> requested_postures(const Config& c)
{
  const CaseOptions o = CaseOptions::from(c);
  std::vector<Posture> p;
  for (const auto& n : o.posture_names)
    p.push_back(named_posture(n));
  for (double t : o.posture_angles_deg)
    p.push_back(posture_from_angle(t));
  return p;
}
} // namespace breastsim
