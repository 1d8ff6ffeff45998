// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// What the planning app shows of a finished job, from its result folder
// (summary.json, the skin surfaces) and its case: per posture the nipple
// (position, distance to the base plane y = 0, the ideal ~60 mm), the
// projection and lowest point; for surgery the resected volume and weight
// (rho), pre and post side by side, and the lower-pole share; for a
// calibration the fitted parameters with their 95 % intervals, their
// identifiability in words and the misfit. And the files of the result the
// API may serve.
#include "config.hpp"
#include "pole_volumes.hpp"
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace breastsim::app
{
/// Ideal distance of the nipple to the base (chest wall) [m], standing.
inline constexpr double ideal_nipple_to_base = 0.06;
/// Ideal share of the breast volume below the nipple (upper:lower 45:55).
inline constexpr double ideal_lower_pole_share = 0.55;

nlohmann::json summarize_result(const std::string& kind, const Config& c,
                                const std::filesystem::path& result_dir);
/// A JSON file of a result (nlohmann's parse error if malformed).
nlohmann::json read_result_json(const std::filesystem::path& file);
/// A fitted parameter's identifiability in words: its flag, else its
/// relative standard error (`relative_se`, null if unknown) in per cent.
std::string identifiability_in_words(const std::string& flag, const nlohmann::json& relative_se);
/// Files of the result folder (as listed in its marker) the API serves:
/// public name (path with '/' -> '_') -> path relative to the job folder.
/// JSON, TOML, HTML, PNG, CSV and text files only.
std::map<std::string, std::string> result_files(const std::filesystem::path& job_folder);
} // namespace breastsim::app
