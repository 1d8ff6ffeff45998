// SPDX-License-Identifier: LGPL-3.0-or-later
#include "sweep_request.hpp"
#include "errors.hpp"
#include <algorithm>
#include <fmt/format.h>

namespace breastsim::app
{
namespace
{
constexpr std::size_t max_keys = 2, max_values = 3;

bool incision_key(const std::string& key)
{
  return key == "incision.a_deg" || key == "incision.s" || key == "incision.h" || key == "incision.d";
}
} // namespace

SweepGrid sweep_grid(const nlohmann::json& vary, const Config& base)
{
  if (!vary.is_object() || vary.empty() || vary.size() > max_keys)
    throw InputError(fmt::format("vary: an object of 1 to {} of a, s, h, d with their values, such as "
                                 "{{\"a\": [25, 30, 35], \"h\": [0.02, 0.025, 0.03]}}",
                                 max_keys));
  SweepGrid grid;
  for (const auto& [name, values] : vary.items())
  {
    const std::string key = sweep_key(name);
    if (!incision_key(key))
      throw InputError("vary: '" + name + "' is not one of the incision's a, s, h, d");
    if (std::any_of(grid.begin(), grid.end(), [&](const auto& g) { return g.first == key; }))
      throw InputError("vary: " + key + " is named twice");
    if (!values.is_array() || values.empty() || values.size() > max_values)
      throw InputError(fmt::format("vary.{}: an array of 1 to {} numbers", name, max_values));
    std::string list;
    for (const auto& v : values)
    {
      if (!v.is_number())
        throw InputError(fmt::format("vary.{}: {} is not a number", name, v.dump().substr(0, 40)));
      list += fmt::format("{}{:.17g}", list.empty() ? "" : ",", v.get<double>());
    }
    grid.emplace_back(key, sweep_values(base, key, list));
    for (const auto& v : grid.back().second)
    {
      Config probe = base; // each value in its key's range, with the case's message
      probe.set(key, v);
      probe.validate();
    }
  }
  check_sweep_request(base, grid);
  return grid;
}

std::size_t sweep_size(const nlohmann::json& vary)
{
  std::size_t n = 1;
  for (const auto& [name, values] : vary.items())
    n *= values.size();
  return n;
}
} // namespace breastsim::app
