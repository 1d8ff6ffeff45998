// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Checks of a triangulated scan's connectivity, each throwing an InputError
// naming the triangle(s), vertex indices and coordinates: degenerate and
// duplicated triangles, non-manifold edges (more than two triangles),
// inconsistent orientation (an edge walked the same way by its two
// triangles), several disconnected pieces. And the open boundary of the
// surface as closed loops of vertex indices.
#include "scan_surface.hpp"
#include <vector>

namespace breastsim::scan
{
void check_degenerate_triangles(const ScanSurface& s);
void check_duplicated_triangles(const ScanSurface& s);
void check_edges(const ScanSurface& s); ///< non-manifold, then orientation
void check_connected(const ScanSurface& s);

/// The boundary edges (in one triangle only) chained into closed loops; an
/// InputError when a boundary vertex has more than two boundary edges (two
/// loops touching) or a chain does not close.
std::vector<std::vector<std::int64_t>> boundary_loops(const ScanSurface& s);

/// Length of a closed loop of vertex indices.
double loop_length(const ScanSurface& s, const std::vector<std::int64_t>& loop);
} // namespace breastsim::scan
