// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Neighbourhoods of a posture's recorded points: the k nearest points of
// each, and the neighbourhood RMS of a per-point quantity.
#include "recording.hpp"
#include <cstddef>
#include <vector>

namespace breastsim::diagnosis
{
using calibration::Point;

using Neighbours = std::vector<std::vector<std::size_t>>;

/// The k nearest other points of each point (brute force; k < pts.size()).
Neighbours nearest_neighbours(const std::vector<Point>& pts, int k);

/// Per point i: sqrt(mean of v_j^2 over j in {i} and its neighbours).
std::vector<double> neighbourhood_rms(const std::vector<double>& v, const Neighbours& knn);
} // namespace breastsim::diagnosis
