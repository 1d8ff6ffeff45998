// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Patient postures (docs/MODEL.md): gravity in the body frame as a function of the
// angle theta between the chest and the vertical,
//   g_vec = -g (cos(theta) e_z + sin(theta) e_y).
#include "config.hpp"
#include <array>
#include <string>
#include <vector>

namespace breastsim
{
struct Posture
{
  std::string name;
  double theta_deg = 0;
};

/// Named posture: standing (0), supine (90), all_fours / prone (-90).
Posture named_posture(const std::string& name);
/// Posture by angle, named "theta_<deg>".
Posture posture_from_angle(double theta_deg);
std::array<double, 3> gravity_vector(double theta_deg, double g);
/// The postures requested by the case (names first, then angles).
std::vector<Posture> requested_postures(const Config& c);
} // namespace breastsim
