// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The breast's volume in front of the chest wall and its lower pole, from a
// skin surface document: one definition for the result tables and the sweep.
#include <nlohmann/json.hpp>

namespace breastsim
{
/// The volume between a half-breast skin surface document
/// (surface_<posture>.json, deformed vertices) and the chest-wall plane
/// y = 0, by the divergence theorem with F = (0, y, 0) (zero on that plane,
/// tangential to the symmetry plane x = 0 and to the horizontal cut at the
/// nipple), and its part below the nipple height z (triangles split by their
/// centroid's height). The springs move the base a few mm off y = 0 (into
/// the chest lying supine, off it at the top standing): the volume in front
/// of the chest wall differs from the body's by up to ~5 %. Half-model
/// volumes [m^3].
struct PoleVolumes
{
  double lower = 0, total = 0;
};
PoleVolumes pole_volumes(const nlohmann::json& surface, double z_nipple);
/// The lower pole's share of the volume in front of the chest wall (0 if
/// there is none).
double lower_pole_share(const nlohmann::json& surface, double z_nipple);
} // namespace breastsim
