// SPDX-License-Identifier: LGPL-3.0-or-later
#include "case_request.hpp"
#include "errors.hpp"
#include "posture.hpp"
#include "schema.hpp"
#include <fmt/format.h>

namespace breastsim::app
{
namespace
{
/// A JSON scalar as the text `--set` would carry.
std::string scalar_text(const std::string& key, const nlohmann::json& v)
{
  if (v.is_string())
    return v.get<std::string>();
  if (v.is_boolean())
    return v.get<bool>() ? "true" : "false";
  if (v.is_number())
    return v.dump();
  throw InputError(fmt::format("key '{}' = {}: expected a number, a string or true/false", key,
                               v.dump().substr(0, 80)));
}

std::string value_text(const std::string& key, const nlohmann::json& v)
{
  if (!v.is_array())
    return scalar_text(key, v);
  std::string text;
  for (const auto& item : v)
  {
    if (!text.empty())
      text += ',';
    text += scalar_text(key, item);
  }
  return text;
}
} // namespace

Config case_from_overrides(const nlohmann::json& overrides)
{
  if (!overrides.is_object())
    throw InputError(fmt::format("the case overrides must be a JSON object {{\"key\": value, ...}}, "
                                 "got {}", overrides.type_name()));
  Config c;
  for (const auto& [key, v] : overrides.items())
  {
    c.set_text(key, value_text(key, v));
    if (key_info(key).path && !c.text(key).empty())
      throw InputError(fmt::format("key '{}' = \"{}\" is not accepted by breastsim serve (no file path "
                                   "from a request: a scan is uploaded as a file): allowed \"\"",
                                   key, c.text(key).substr(0, 80)));
    if (key == "solver.petsc_options" && !c.text(key).empty())
      throw InputError(fmt::format("key 'solver.petsc_options' = \"{}\" is not accepted by breastsim "
                                   "serve (PETSc options can name files): allowed \"\"",
                                   c.text(key).substr(0, 80)));
  }
  c.validate();
  return c;
}

std::size_t posture_count(const Config& c)
{
  return requested_postures(c).size();
}
} // namespace breastsim::app
