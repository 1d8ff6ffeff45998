// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Several scans of one breast in different postures, for a calibration:
// the first is meshed as `scan-model` meshes a scan
// (scan_model.hpp); every further scan is read, checked and fitted the same
// way (the same refusals, and its robust noise RMS), and its points are
// mapped into the first scan's breast frame. The scans must share one
// chest-fixed frame: the chest wall (`chest`, the same surface for every
// scan) does not move between postures, so the first scan's frame is every
// scan's. Runs on one process; every refusal is an InputError naming the scan.
#include "scan_model.hpp"
#include <filesystem>
#include <vector>

namespace breastsim::scan
{
struct SeriesScan
{
  std::filesystem::path file;
  std::vector<Vec3> points; ///< the scan's skin points in the first scan's breast frame [m]
  double noise_rms = 0;     ///< robust RMS of its points about its own smooth fit [m]
  double fit_rms = 0;
};

struct ScanSeries
{
  ScanModel first;              ///< the first scan, meshed (breast frame)
  std::vector<Vec3> first_points; ///< its skin points in its breast frame [m]
  std::vector<SeriesScan> others; ///< in the order given
  ScanMesh coarse;                ///< with coarse_ratio > 0: the first scan meshed coarse_ratio times coarser
};

/// The series: `skins[0]` meshed, the others fitted and mapped. `chest` is
/// required (it registers the scans). With `coarse_ratio` > 0 the first
/// scan's fit is also meshed at coarse_ratio times its mesh size (the
/// discretisation error of a calibration).
ScanSeries build_scan_series(const std::vector<std::filesystem::path>& skins, const std::filesystem::path& chest,
                             const ScanModelOptions& o, int tag_base, int tag_skin, int tag_symmetry,
                             double coarse_ratio = 0);
} // namespace breastsim::scan
