// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The files of a calibration (calibrated.toml, report.json, the surfaces and
// the pictures) and its printable summary.
#include "calibrate.hpp"
#include "output_target.hpp"
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <string>

namespace breastsim::calibration
{
struct CalibrationOutputOptions
{
  bool pictures = true;            ///< PNGs (calibration_plots.py, render.py)
  std::string picture_size = "800x600";
};

/// Write calibrated.toml, report.json, surface_<posture>.json and (with
/// `pictures`) misfit_history.png, measurements.png, view_<posture>.png and
/// overview.png into `out` (staged: replaced only when all are written).
void write_calibration(const CalibrationResult& r, const OutputTarget& out, MPI_Comm comm,
                       const CalibrationOutputOptions& o = {});

/// Printable summary: fitted values with intervals and flags.
std::string calibration_table(const nlohmann::json& report);
} // namespace breastsim::calibration
