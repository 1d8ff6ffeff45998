// SPDX-License-Identifier: LGPL-3.0-or-later
#include "schema.hpp"
#include "errors.hpp"
#include "strings.hpp"
#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>

namespace breastsim
{
namespace
{
constexpr double inf = std::numeric_limits<double>::infinity();
} // namespace

KeyInfo number_key(std::string key, std::string unit, double def, double lo, double hi,
                   std::string doc, bool lo_open)
{
  return KeyInfo{std::move(key), KeyType::number, std::move(unit), def, lo, hi, lo_open, {},
                 std::move(doc)};
}

KeyInfo upper_bound_open(KeyInfo k)
{
  k.hi_open = true;
  return k;
}

KeyInfo integer_key(std::string key, std::int64_t def, double lo, double hi, std::string doc)
{
  return KeyInfo{std::move(key), KeyType::integer, "", def, lo, hi, false, {}, std::move(doc)};
}

KeyInfo boolean_key(std::string key, bool def, std::string doc)
{
  return KeyInfo{std::move(key), KeyType::boolean, "", def, -inf, inf, false, {}, std::move(doc)};
}

KeyInfo choice_key(std::string key, std::string def, std::vector<std::string> choices,
                   std::string doc)
{
  return KeyInfo{std::move(key), KeyType::string, "", std::move(def), -inf, inf, false,
                 std::move(choices), std::move(doc)};
}

KeyInfo text_key(std::string key, std::string def, std::string doc)
{
  return KeyInfo{std::move(key), KeyType::string, "", std::move(def), -inf, inf, false, {},
                 std::move(doc)};
}

std::string type_name(KeyType t)
{
  switch (t)
  {
  case KeyType::number: return "number";
  case KeyType::integer: return "integer";
  case KeyType::boolean: return "boolean";
  case KeyType::string: return "string";
  case KeyType::number_list: return "list of numbers";
  case KeyType::string_list: return "list of strings";
  }
  return "?";
}

std::string range_text(const KeyInfo& k)
{
  if (!k.choices.empty())
    return fmt::format("one of {}", fmt::join(k.choices, ", "));
  if (k.type == KeyType::boolean)
    return "true or false";
  if (k.type == KeyType::string)
    return "any text";
  return fmt::format("{}{}, {}{}", k.lo_open ? "(" : "[", k.lo, k.hi, k.hi_open ? ")" : "]");
}

std::string value_text(const Value& v)
{
  return std::visit(
      [](const auto& x) -> std::string
      {
        using X = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<X, std::string>)
          return "\"" + x + "\"";
        else if constexpr (std::is_same_v<X, bool>)
          return x ? "true" : "false";
        else if constexpr (std::is_same_v<X, std::vector<std::string>>)
        {
          std::vector<std::string> q;
          for (auto& s : x)
            q.push_back("\"" + s + "\"");
          return fmt::format("[{}]", fmt::join(q, ", "));
        }
        else if constexpr (std::is_same_v<X, std::vector<double>>)
          return fmt::format("[{}]", fmt::join(x, ", "));
        else
          return fmt::format("{}", x);
      },
      v);
}

const KeyInfo& key_info(const std::string& key)
{
  for (const auto& k : schema())
    if (k.key == key)
      return k;
  // Suggest the likely misspelling, else the keys of the same section.
  std::vector<std::string> all, near;
  const std::string section = key.substr(0, key.find('.'));
  for (const auto& k : schema())
  {
    all.push_back(k.key);
    if (k.key.rfind(section + ".", 0) == 0)
      near.push_back(k.key);
  }
  if (const std::string guess = closest_match(key, all); !guess.empty())
    throw InputError(fmt::format("unknown key '{}': did you mean '{}'? (see `breastsim keys`)",
                                 shorten(key), guess));
  throw InputError(fmt::format("unknown key '{}'{}", shorten(key),
                               near.empty() ? std::string(" (see `breastsim keys`)")
                                            : fmt::format(" (keys of [{}]: {})", section,
                                                          fmt::join(near, ", "))));
}

std::string schema_markdown()
{
  std::string s = "| key | type | unit | default | allowed | meaning |\n|---|---|---|---|---|---|\n";
  for (const auto& k : schema())
    s += fmt::format("| `{}` | {} | {} | `{}` | {} | {} |\n", k.key, type_name(k.type), k.unit,
                     value_text(k.default_value), range_text(k), k.doc);
  return s;
}
} // namespace breastsim
