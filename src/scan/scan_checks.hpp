// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The checks that refuse a dirty scan, each with an InputError naming what
// is wrong and where (vertex or triangle index, coordinates in the stated
// unit). Before the fit (check_scan): an empty file, non-finite
// coordinates, too few points, implausible size for the stated unit,
// degenerate, duplicated, non-manifold, inconsistently oriented,
// disconnected and self-intersecting triangles. The frame's own checks are
// in scan_frame.hpp (footprint, holes, wrong side). After the fit
// (check_fit): spikes, noise beyond the bound, gaps the fit would have to
// invent, folds (the skin is not star-shaped about the base centre).
#include "radial_fit.hpp"
#include "scan_frame.hpp"
#include "scan_surface.hpp"

namespace breastsim::scan
{
struct ScanLimits
{
  std::size_t min_points = 300;             ///< fewest points of a skin scan
  double min_extent = 0.04, max_extent = 0.6; ///< plausible size of a breast scan [m]
  double max_hole = 0.025;                  ///< widest hole bridged by the fit [m]
  double max_noise = 0.002;                 ///< largest robust RMS distance to the fitted surface [m]
  double max_spike = 0.006;                 ///< a point farther than this (and 8 noise RMS) is a spike [m]
  double max_chest_rms = 0.003;             ///< largest RMS distance of the chest wall from the chest plane [m]
};

/// The raw checks of a skin scan (or, with `chest`, of a chest-wall surface: no count or size bound).
void check_scan(const ScanSurface& s, const ScanLimits& l, bool chest = false);

/// The points of `s` that the fit uses: every point of a cloud, the
/// vertices of the triangles of a triangulated scan (stray vertices are
/// ignored), as indices.
std::vector<std::size_t> fit_points(const ScanSurface& s);

/// The checks of the fitted surface against the scan: `residuals` are the
/// radial distances of the points `used` (indices into s.points).
void check_fit(const ScanSurface& s, const BreastFrame& f, const RadialSurface& fit,
               const std::vector<std::size_t>& used, const std::vector<double>& residuals, const ScanLimits& l);

/// Robust RMS of `r`: 1.4826 median |r| (the standard deviation for Gaussian noise).
double robust_rms(std::vector<double> r);
} // namespace breastsim::scan
