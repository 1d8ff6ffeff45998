// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// How far the chest wall is from the chest plane that the mesh's base lies
// on (the scan's mesh has a planar base, y = 0 of the breast frame). The
// chest wall under the breast is sampled: with a chest surface (--chest),
// its points and points spread over its triangles whose projection lies
// within 1.2 footprint radii of the frame's origin; without one, the
// footprint loop (the only place where the scan meets the chest). The
// samples' distances to the plane give its RMS and largest distance; with a
// chest surface a quadric graph y = q(x, z) (6 coefficients, least squares)
// is fitted through them too and gives the chest's principal curvature
// radii. A closed footprint curve does not determine a quadric (any
// multiple of its own equation can be added), so none is fitted to it.
#include "scan_frame.hpp"
#include "scan_surface.hpp"
#include <array>
#include <string>

namespace breastsim::scan
{
struct ChestCurvature
{
  std::string source;            ///< "chest surface" or "footprint"
  std::size_t samples = 0;       ///< points of the chest wall measured
  double plane_rms = 0;          ///< RMS distance of the samples from the chest plane [m]
  double plane_max = 0;          ///< largest distance [m]
  bool quadric = false;          ///< a quadric graph was fitted (a chest surface)
  double quadric_rms = 0;        ///< RMS distance of the samples from the quadric [m]
  /// Principal curvature radii of the quadric at the origin, signed (> 0: the
  /// chest bulges toward the breast), the smaller magnitude first; +-inf: flat.
  std::array<double, 2> curvature_radii{0, 0};
};

/// Measure the chest wall (`chest`, may be null: the footprint of `skin`)
/// against the plane y = 0 of `frame`.
ChestCurvature measure_chest(const BreastFrame& frame, const ScanSurface& skin, const ScanSurface* chest);

/// InputError when the plane misrepresents the chest wall: its RMS distance
/// above `max_rms` [m] (the option --max-chest-rms), naming both.
void check_chest_curvature(const ChestCurvature& c, double max_rms, const std::string& where);
} // namespace breastsim::scan
