// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The WHERE step of a diagnosis: regions of systematic residual on each
// posture's recorded points.
#include "diagnosis.hpp"
#include <vector>

namespace breastsim::diagnosis
{
/// Regions of systematic residual of one fit (neighbourhood means of its
/// whitened residuals f.r, d_i / sigma_eff,i; clusters of same-sign points
/// beyond region_z), largest |z| first.
std::vector<Region> locate_regions(const Recording& rec, const FitState& f, int neighbours,
                                   double region_z);
} // namespace breastsim::diagnosis
