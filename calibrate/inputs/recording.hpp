// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// 3D surface recordings of one breast in several postures (README,
// "Recording format"): unordered skin points of the half breast (x >= 0) per
// posture, optional landmarks, the noise sigma, and parameters known a
// priori. SI units. Read once here and checked; messages name the key.
#include <array>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace breastsim::calibration
{
using Point = std::array<double, 3>;

struct RecordedPosture
{
  std::string name;
  double theta_deg = 0;
  std::vector<Point> points;        ///< skin samples [m]
  std::optional<Point> nipple;      ///< landmark "nipple" [m]
};

struct Recording
{
  double noise_sigma = 0;                 ///< standard deviation of each coordinate [m]
  std::map<std::string, double> known;    ///< a-priori values: R, H, rho
  std::vector<RecordedPosture> postures;
  std::string source;                     ///< where it was read from (messages, reports)
  /// Ground truth of synthetic recordings (never read by the diagnosis).
  nlohmann::json truth;
};

inline constexpr const char* recording_format = "breastsim-recording/1";
/// The most points a recorded posture may hold (`record --points` writes at most as many).
inline constexpr std::size_t max_recorded_points = 1000000;

/// Parse and check a recording document; `source` names it in messages.
/// Throws InputError naming the key, the value and the allowed range.
Recording parse_recording(const nlohmann::json& j, const std::string& source);
Recording read_recording(const std::filesystem::path& file);
/// True if the document's "format" is recording_format.
bool is_recording(const nlohmann::json& doc);
nlohmann::json to_json(const Recording& r);
} // namespace breastsim::calibration
