// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// From a skin scan (and optionally a chest-wall surface) to a tagged
// tetrahedral mesh in the breast frame: read (scan_readers.hpp), refuse a
// dirty scan (scan_checks.hpp), find the chest plane, frame and nipple
// (scan_frame.hpp), measure the chest wall against that plane and refuse a
// chest too curved for it (chest_curvature.hpp), fit the smooth star-shaped
// skin (radial_fit.hpp), check the fit against the points, and mesh the body
// under it (scan_mesh.hpp).
// Runs on one process; every refusal is an InputError.
#include "chest_curvature.hpp"
#include "radial_fit.hpp"
#include "scan_checks.hpp"
#include "scan_frame.hpp"
#include "scan_mesh.hpp"
#include <filesystem>
#include <optional>

namespace breastsim::scan
{
struct ScanModelOptions
{
  Units units = Units::mm;
  FrameOptions frame;
  ScanLimits limits;
  ScanMeshOptions mesh;
  int degree = 10;          ///< total degree of the Chebyshev fit
  double smoothing = 1e-7;  ///< fit penalty relative to the normal equations' mean diagonal
};

struct ScanModel
{
  BreastFrame frame;
  ChestCurvature chest;  ///< the chest wall against the chest plane (the mesh's base)
  RadialSurface fit;
  ScanMesh mesh;
  std::size_t points = 0, triangles = 0, points_used = 0;
  double fit_rms = 0;    ///< RMS radial distance of the scan points to the fitted skin [m]
  double noise_rms = 0;  ///< robust RMS of the same [m]
  double mesh_size = 0;  ///< of the mesh [m]
  bool half = false;     ///< the mesh is the half x >= 0
};

ScanModel build_scan_model(const std::filesystem::path& skin, const std::optional<std::filesystem::path>& chest,
                           const ScanModelOptions& o, int tag_base, int tag_skin, int tag_symmetry);

/// The fit alone (no mesh): read, check, frame, fit, check the fit.
ScanModel fit_scan(const ScanSurface& skin, const ScanSurface* chest, const ScanModelOptions& o);
} // namespace breastsim::scan
