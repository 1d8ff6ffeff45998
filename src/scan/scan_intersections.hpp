// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Self-intersection of a triangulated scan: two triangles that share no
// vertex and cross each other (an edge of one passes through the other).
// Candidate pairs come from a uniform grid of triangle bounding boxes.
#include "scan_surface.hpp"

namespace breastsim::scan
{
/// InputError naming the first pair of crossing triangles and a point where they cross.
void check_self_intersections(const ScanSurface& s);
} // namespace breastsim::scan
