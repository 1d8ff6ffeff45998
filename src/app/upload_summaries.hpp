// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// What the planning app shows of a job made from an uploaded file: a
// calibration from a 3D surface recording (the point-to-skin fit of the
// diagnosis: diagnosis.json) and a scan job (scan-model -> neutral-state ->
// simulate: the scanned breast in each posture).
#include "config.hpp"
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace breastsim::app
{
/// A recording's calibration in the shape of a measurements calibration's
/// summary (parameters with start, fitted value, 95 % interval and
/// identifiability in words, fitted_overrides; chi2_before is null: the
/// diagnosis reports the fitted misfit only) plus "data": "recording" and
/// per posture the RMS distance of the points to the fitted skin.
nlohmann::json summarize_recording_fit(const Config& start, const std::filesystem::path& result_dir);

/// A scan job's summary from its job folder: the scan model (points,
/// triangles, fit and noise RMS, nipple, footprint radius, tetrahedra,
/// volume), the neutral state (iterations, final mismatch), and the
/// simulated postures of result/ as a simulation's summary.
nlohmann::json summarize_scan(const Config& c, const std::filesystem::path& job_folder);

/// The files of a scan job the API serves besides result/: the model's and
/// the neutral state's summaries and the neutral case.
std::map<std::string, std::string> scan_files();
} // namespace breastsim::app
