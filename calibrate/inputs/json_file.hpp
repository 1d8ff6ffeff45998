// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Read a JSON input document once, with the project's messages: the file
// cannot be read, is too large, is not valid JSON, or repeats a key (InputError).
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace breastsim::calibration
{
/// The largest JSON input read (bytes): a recording of 1,000,000 points in
/// each of two postures fits.
inline constexpr std::uintmax_t max_json_bytes = 128u << 20;

/// `what` names the document in messages, e.g. "measurements file".
nlohmann::json read_json_file(const std::filesystem::path& file, const std::string& what);
} // namespace breastsim::calibration
