// SPDX-License-Identifier: LGPL-3.0-or-later
#include "strict_json.hpp"
#include <set>
#include <vector>

namespace breastsim
{
nlohmann::json parse_json_strict(const std::string& text)
{
  std::vector<std::set<std::string>> open_objects; // keys seen in each open object
  using Event = nlohmann::json::parse_event_t;
  auto check_keys = [&](int, Event event, nlohmann::json& parsed)
  {
    if (event == Event::object_start)
      open_objects.emplace_back();
    else if (event == Event::object_end)
      open_objects.pop_back();
    else if (event == Event::key && !open_objects.back().insert(parsed.get<std::string>()).second)
      throw DuplicateJsonKey(parsed.get<std::string>());
    return true;
  };
  return nlohmann::json::parse(text, check_keys);
}
} // namespace breastsim
