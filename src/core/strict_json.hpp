// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// JSON from users, parsed strictly: a key given twice in one object is an
// error (nlohmann-json would keep the last value silently).
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace breastsim
{
/// A key that appears twice in one JSON object.
class DuplicateJsonKey : public std::runtime_error
{
public:
  explicit DuplicateJsonKey(const std::string& key)
      : std::runtime_error("the key '" + key + "' appears twice in one object"), key(key)
  {
  }
  std::string key;
};

/// Parse `text`; throws nlohmann::json::exception for malformed JSON and
/// DuplicateJsonKey for a repeated key.
nlohmann::json parse_json_strict(const std::string& text);
} // namespace breastsim
