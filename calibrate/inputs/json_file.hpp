#pragma once
// Read a JSON input document once, with the project's messages: the file
// cannot be read, or it is not valid JSON (InputError).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace breastsim::calibration
{
/// `what` names the document in messages, e.g. "measurements file".
nlohmann::json read_json_file(const std::filesystem::path& file, const std::string& what);
} // namespace breastsim::calibration
