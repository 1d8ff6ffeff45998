// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// What `breastsim calibrate` is asked (after the command line is parsed),
// checked against the starting case before a long fit, and its data file
// read and routed by its format: point measurements (measurements.hpp) or a
// 3D surface recording (recording.hpp).
#include "config.hpp"
#include "measurements.hpp"
#include "recording.hpp"
#include <optional>
#include <string>

namespace breastsim::calibration
{
struct CalibrateRequest
{
  std::string data_file;               ///< measurements (JSON) or a 3D surface recording
  std::string fit = "mu,c";            ///< --fit names
  std::string algorithm = "lm";        ///< optimizer.hpp
  int max_evals = 200;                 ///< in total with --resume
  bool resume = false;
  bool remesh = false;                 ///< remesh for R, H instead of morphing
  double correction_mesh_size = 0;     ///< > 0: model-error correction from this mesh [m]
  std::string picture_size = "800x600";
  int ranks_per_case = 0;              ///< MPI ranks per forward solve (0: all)
};

/// --max-evals >= 1; --correction-mesh-size 0 or in (0, geometry.mesh_size)
/// and inside the schema's range of mesh sizes; --size WIDTHxHEIGHT with both
/// in [100, 8000]. Throws InputError naming the option.
void check_calibrate_request(const CalibrateRequest& r, const Config& start);

/// The data of a calibration, read and checked (InputError).
struct CalibrationData
{
  std::optional<Recording> recording; ///< 3D surface points: the point-to-skin fit
  Measurements measurements;          ///< otherwise: point measurements
};
CalibrationData read_calibration_data(const std::string& file);
} // namespace breastsim::calibration
