// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Pictures of a calibration result folder: the plots of report.json made by
// src/viewer/calibration_plots.py (misfit history, measured vs model per
// measurement) and the breast pictures of the calibrated model made by the
// picture pipeline of `simulate` (render_pictures on surface_<posture>.json).
#include <filesystem>
#include <mpi.h>
#include <string>

namespace breastsim::calibration
{
/// Collective. Writes misfit_history.png, measurements.png, view_<posture>.png
/// and overview.png (size "WxH") into `dir`. Throws (InputError for a bad
/// size, std::runtime_error otherwise) if a script fails.
void render_calibration_pictures(const std::filesystem::path& dir, const std::string& size,
                                 MPI_Comm comm);
} // namespace breastsim::calibration
