// SPDX-License-Identifier: LGPL-3.0-or-later
#include "pole_volumes.hpp"
#include <vector>

namespace breastsim
{
PoleVolumes pole_volumes(const nlohmann::json& surface, double z_nipple)
{
  const auto x = surface.at("vertices").get<std::vector<double>>();
  const auto t = surface.at("triangles").get<std::vector<std::int64_t>>();
  PoleVolumes v;
  for (std::size_t k = 0; k + 2 < t.size(); k += 3)
  {
    const double* a = &x.at(3 * t[k]);
    const double* b = &x.at(3 * t[k + 1]);
    const double* c = &x.at(3 * t[k + 2]);
    // y component of (b - a) x (c - a) / 2: the oriented area projected on y
    const double ny = 0.5 * ((b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]));
    const double part = (a[1] + b[1] + c[1]) / 3 * ny;
    v.total += part;
    if ((a[2] + b[2] + c[2]) / 3 < z_nipple)
      v.lower += part;
  }
  return v;
}

double lower_pole_share(const nlohmann::json& surface, double z_nipple)
{
  const PoleVolumes v = pole_volumes(surface, z_nipple);
  return v.total > 0 ? v.lower / v.total : 0.0;
}
} // namespace breastsim
