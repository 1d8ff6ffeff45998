// SPDX-License-Identifier: LGPL-3.0-or-later
#include "json_file.hpp"
#include "errors.hpp"
#include "input_file.hpp"
#include "strict_json.hpp"
#include <fmt/format.h>
#include <fstream>
#include <sstream>

namespace breastsim::calibration
{
nlohmann::json read_json_file(const std::filesystem::path& file, const std::string& what)
{
  check_input_file(file, what);
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(file, ec);
  if (!ec && bytes > max_json_bytes)
    throw InputError(fmt::format("{} '{}' is {} MB: allowed at most {} MB", what, file.string(),
                                 bytes >> 20, max_json_bytes >> 20));
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in)
    throw InputError(fmt::format("{} '{}' cannot be read", what, file.string()));
  try
  {
    return parse_json_strict(text.str());
  }
  catch (const DuplicateJsonKey& e)
  {
    throw InputError(fmt::format("{} '{}' is ambiguous: {} (give each key once)", what,
                                 file.string(), e.what()));
  }
  catch (const nlohmann::json::out_of_range& e) // e.g. 1e999: beyond the range of a double
  {
    throw InputError(fmt::format("{} '{}' holds a number beyond the range of a double "
                                 "(|x| < 1.8e308): {}",
                                 what, file.string(), plain_error(e)));
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(fmt::format("{} '{}' is not valid JSON (NaN and Infinity are not JSON "
                                 "numbers): {}",
                                 what, file.string(), plain_error(e)));
  }
}
} // namespace breastsim::calibration
