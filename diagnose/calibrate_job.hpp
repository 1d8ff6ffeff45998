// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// `breastsim calibrate` as a job: the request with its data, read and checked
// before any output is claimed; the fit (calibrate.hpp for point
// measurements; for a 3D surface recording the point-to-skin fit of the
// diagnosis without discovery, diagnose.hpp) and the files it writes. The
// CLI parses, claims the outputs and prints the summary. In the diagnosis
// layer because it runs either.
#include "calibrate_request.hpp"
#include "fit_parameters.hpp"
#include "output_target.hpp"
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <mpi.h>
#include <string>
#include <vector>

namespace breastsim::diagnosis
{
struct CalibrateJob
{
  Config start;
  calibration::CalibrateRequest request;
  calibration::CalibrationData data;
  std::vector<calibration::FitParameter> fit; ///< point measurements: the parsed --fit
  /// Point measurements: called after every evaluation with its history
  /// entry (CalibrateOptions::on_evaluation).
  std::function<void(const nlohmann::json&)> on_evaluation;

  /// Point measurements keep a checkpoint (--checkpoint, --resume); a recording's fit does not.
  bool keeps_checkpoint() const { return !data.recording.has_value(); }
};

/// Read the data file; for point measurements also the --fit list and the
/// algorithm. Throws InputError.
CalibrateJob prepare_calibration(const Config& start, const calibration::CalibrateRequest& r);

/// Collective. Fit and write every result file into `out` (staged, replaced
/// only when complete); the printable summary on rank 0, ending in
/// "results written to ..." ("" on the other ranks).
std::string run_calibration(const CalibrateJob& job, const OutputTarget& out,
                            const std::filesystem::path& checkpoint, MPI_Comm comm);
} // namespace breastsim::diagnosis
