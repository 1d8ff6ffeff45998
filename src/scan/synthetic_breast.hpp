// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Synthetic patients' reference (stress-free) breasts, not caps: in the
// breast frame, the body under the skin of a distorted half ellipsoid,
//   g(x) = (xi / a_s)^2 + ((y + y0) / b)^2 + (zeta / c_s)^2 = 1,
//   xi = x - lateral a (y / b),  zeta = z + ptosis c (y / b)^2,
// with a_s = a (1 + asymmetry) on the lateral side (xi > 0), a (1 -
// asymmetry / 2) on the medial side, c_s = c (1 - asymmetry / 2) above
// (zeta > 0) and c (1 + asymmetry / 2) below, cut by the chest plane y = 0.
// lateral turns the nipple toward the axilla, ptosis lets the anterior part
// hang, asymmetry makes the lateral and lower quadrants fuller. The skin is
// fitted as a RadialSurface (radial_fit.hpp) and scaled to the volume.
#include "radial_fit.hpp"

namespace breastsim::scan
{
struct SyntheticShape
{
  double volume = 500e-6;   ///< [m^3], 200 to 1500 cm^3
  double ptosis = 0.3;      ///< droop of the anterior part, in [0, 0.8]
  double lateral = 0.1;     ///< nipple turned laterally, in [-0.4, 0.4]
  double asymmetry = 0.15;  ///< in [0, 0.4]
  double aspect = 0.8;      ///< height b over the footprint semi-axis a, in [0.4, 1.2]
};

/// The reference skin of `s` (InputError naming a parameter out of range).
RadialSurface synthetic_reference(const SyntheticShape& s);
} // namespace breastsim::scan
