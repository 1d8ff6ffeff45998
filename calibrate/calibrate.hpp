#pragma once
// `breastsim calibrate`: fit case parameters to measurements (the paper's
// parameter finder). Orchestrates forward model, objective, optimiser,
// checkpoint and uncertainty; returns the calibrated case and the report.
#include "fit_parameters.hpp"
#include "measurements.hpp"
#include "optimizer.hpp"
#include <filesystem>
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
};

struct CalibrationResult
{
  Config calibrated;      ///< the input case with the fitted values set
  nlohmann::json report;  ///< see docs/CALIBRATION.md
};

CalibrationResult calibrate(const Config& start, const Measurements& data,
                            const std::vector<FitParameter>& fit, const CalibrateOptions& o,
                            MPI_Comm comm);

/// Write calibrated.toml and report.json into `out` (staged: replaced only
/// when both are written).
void write_calibration(const CalibrationResult& r, const std::filesystem::path& out, MPI_Comm comm);

/// Printable summary: fitted values with intervals and flags.
std::string calibration_table(const nlohmann::json& report);
} // namespace breastsim::calibration
