// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The surgery section of the schema: the incision (IncisionSpec) and the
// accepted suture gap.
#include "config.hpp"
#include "geometry_options.hpp"
#include <vector>

namespace breastsim
{
struct SurgeryOptions
{
  IncisionSpec incision; ///< incision.*
  double max_gap = 1e-4; ///< surgery.max_gap: largest suture gap accepted [m]

  bool operator==(const SurgeryOptions&) const = default;
  /// Append incision.* and surgery.max_gap (defaults: the initialisers above).
  static void declare(std::vector<KeyInfo>& keys);
  static SurgeryOptions from(const Config& c);
};
} // namespace breastsim
