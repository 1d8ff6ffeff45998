// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The breast frame of a scan (docs/MODEL.md, "Full breast and patient scans"): y
// along the outward chest normal, z cranial, x lateral, the origin on the
// chest plane. The chest plane is fitted through the scan's footprint (the
// longest open boundary loop of a triangulated skin) or through a second
// surface, the chest wall. The origin is the footprint's centroid, moved
// along x into the sagittal plane of the nipple (so the nipple has x = 0;
// the incision is built in that plane). The nipple is a landmark given by
// the user, else the most anterior part of the skin.
#include "scan_surface.hpp"
#include <optional>
#include <vector>

namespace breastsim::scan
{
struct FrameOptions
{
  Vec3 up{0, 0, 1};           ///< the cranial direction in the scanner frame
  Vec3 lateral{1, 0, 0};      ///< toward the axilla of this breast, scanner frame
  std::optional<Vec3> nipple; ///< landmark in the scanner frame [m]
};

struct BreastFrame
{
  Vec3 origin{};                    ///< scanner frame [m]
  Vec3 ex{}, ey{}, ez{};            ///< unit axes in the scanner frame
  Vec3 nipple{};                    ///< the landmark, or the mean of the most anterior skin points (scanner frame)
  double footprint_radius = 0;      ///< mean distance of the footprint from its centroid [m]
  double footprint_off_plane = 0;   ///< largest distance of a footprint point from the chest plane [m]
  std::vector<std::int64_t> footprint; ///< its vertex loop (empty with a point-cloud skin and a chest)
  /// x x y = -z: a left-handed frame (the scan is mirrored into it).
  bool mirrored() const { return dot(cross(ex, ey), ez) < 0; }
  Vec3 to_breast(const Vec3& p) const
  {
    const Vec3 d = p - origin;
    return {dot(d, ex), dot(d, ey), dot(d, ez)};
  }
  Vec3 to_scanner(const Vec3& q) const { return origin + q[0] * ex + q[1] * ey + q[2] * ez; }
};

/// The frame of `skin`; `chest` (may be null) is the chest wall. InputError
/// naming the defect: no footprint (a closed surface, or a point cloud
/// without a chest), a degenerate or non-planar footprint, the breast on the
/// wrong side of the chest wall, --up or --lateral along the chest normal, a
/// nipple landmark away from the skin. `max_hole`: loops other than the
/// footprint are holes, refused when wider than this [m].
BreastFrame breast_frame(const ScanSurface& skin, const ScanSurface* chest, const FrameOptions& o,
                         double max_hole);
} // namespace breastsim::scan
