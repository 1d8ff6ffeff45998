// SPDX-License-Identifier: LGPL-3.0-or-later
#include "cap_morph.hpp"
#include "half_cap.hpp"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace breastsim::meshes
{
double cap_exit_distance(const CapShape& cap, double dy)
{
  // |s d - (0, yc, 0)| = Rs  =>  s = dy yc + sqrt(dy^2 yc^2 + Rs^2 - yc^2), Rs^2 - yc^2 = R^2.
  const double yc = cap.H - sphere_radius(cap.R, cap.H);
  return dy * yc + std::sqrt(dy * dy * yc * yc + cap.R * cap.R);
}

void morph_cap(std::span<double> x, const CapShape& from, const CapShape& to)
{
  if (!(from.R > 0 && from.H > 0 && to.R > 0 && to.H > 0))
    throw std::invalid_argument("morph_cap: R and H must be > 0");
  if (from.R == to.R && from.H == to.H)
    return;
  for (std::size_t i = 0; i + 2 < x.size(); i += 3)
  {
    const double r = std::sqrt(x[i] * x[i] + x[i + 1] * x[i + 1] + x[i + 2] * x[i + 2]);
    if (r == 0)
      continue; // the base centre is the fixed point of the map
    const double dy = std::clamp(x[i + 1] / r, 0.0, 1.0);
    // p' = p t(dy; to) / t(dy; from)
    const double k = cap_exit_distance(to, dy) / cap_exit_distance(from, dy);
    x[i] *= k;
    x[i + 1] *= k;
    x[i + 2] *= k;
  }
}
} // namespace breastsim::meshes
