#include "json_file.hpp"
#include "errors.hpp"
#include <fmt/format.h>
#include <fstream>

namespace breastsim::calibration
{
nlohmann::json read_json_file(const std::filesystem::path& file, const std::string& what)
{
  if (std::filesystem::is_directory(file))
    throw InputError(fmt::format("{} '{}' is a folder, not a JSON file", what, file.string()));
  std::ifstream in(file);
  if (!in)
    throw InputError(fmt::format("{} '{}' cannot be read", what, file.string()));
  try
  {
    return nlohmann::json::parse(in);
  }
  catch (const nlohmann::json::out_of_range& e) // e.g. 1e999: beyond the range of a double
  {
    throw InputError(fmt::format("{} '{}' holds a number beyond the range of a double "
                                 "(|x| < 1.8e308): {}",
                                 what, file.string(), e.what()));
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(fmt::format("{} '{}' is not valid JSON (NaN and Infinity are not JSON "
                                 "numbers): {}",
                                 what, file.string(), e.what()));
  }
}
} // namespace breastsim::calibration
