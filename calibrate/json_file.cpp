#include "json_file.hpp"
#include "errors.hpp"
#include <fmt/format.h>
#include <fstream>

namespace breastsim::calibration
{
nlohmann::json read_json_file(const std::filesystem::path& file, const std::string& what)
{
  std::ifstream in(file);
  if (!in)
    throw InputError(fmt::format("{} '{}' cannot be read", what, file.string()));
  try
  {
    return nlohmann::json::parse(in);
  }
  catch (const nlohmann::json::parse_error& e)
  {
    throw InputError(fmt::format("{} '{}' is not valid JSON (NaN and Infinity are not JSON "
                                 "numbers): {}",
                                 what, file.string(), e.what()));
  }
}
} // namespace breastsim::calibration
