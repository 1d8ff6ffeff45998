// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// `breastsim calibrate`: fit case parameters to measurements (the paper's
// parameter finder). Orchestrates forward model, objective, optimiser,
// checkpoint and uncertainty; returns the calibrated case and the report.
#include "fit_parameters.hpp"
#include "measurements.hpp"
#include "optimizer.hpp"
#include <filesystem>
#include <functional>
#include <mpi.h>
#include <nlohmann/json.hpp>

namespace breastsim::calibration
{
struct CalibrateOptions
{
  OptimizerOptions optimizer;
  std::filesystem::path checkpoint; ///< written after every evaluation ("" = none)
  bool resume = false;              ///< start from the checkpoint's best point
  std::string measurements_source;  ///< for the report
  bool morph = true;                ///< morph the mesh for R, H (false: remesh, forward_model.hpp)
  /// > 0: after the fit, solve the fitted case on a mesh of this size,
  /// correct the model by the difference d_i = G_fine,i - G_fit,i
  /// (discretisation error of the fit mesh) and fit again from there;
  /// repeated with d at the new optimum (see the two options below).
  double correction_mesh_size = 0;
  int correction_passes = 4;          ///< at most this many corrected fits ...
  /// ... until every ln p moves less than this or than 0.1 of its standard error
  double correction_tolerance = 0.01;
  /// MPI ranks per forward solve: the Jacobian's columns are solved by
  /// groups of this many ranks side by side (0: all ranks on each solve).
  int ranks_per_case = 0;
  /// Called after every evaluation with its history entry ({"evaluation",
  /// "chi2", "stage", "parameters", "best"}, as in report.json), e.g. to
  /// stream the progress of a job.
  std::function<void(const nlohmann::json&)> on_evaluation;
};

struct CalibrationResult
{
  Config calibrated;      ///< the input case with the fitted values set
  nlohmann::json report;  ///< see docs/CALIBRATION.md
  /// Skin surface of the calibrated model in each measured posture
  /// (surface_export.hpp documents), for the pictures.
  std::vector<nlohmann::json> surfaces;
};

CalibrationResult calibrate(const Config& start, const Measurements& data,
                            const std::vector<FitParameter>& fit, const CalibrateOptions& o,
                            MPI_Comm comm);
} // namespace breastsim::calibration
