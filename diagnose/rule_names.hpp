#pragma once
// The names of the diagnosis' rule choices (diagnosis.hpp enums), one table
// per enum: the command line parses them and diagnosis.json reports them.
#include "diagnosis.hpp"
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace breastsim::diagnosis
{
template <class E>
using NameTable = std::vector<std::pair<std::string, E>>;

const NameTable<NoiseFloor>& noise_floor_names();                   ///< posture, local
const NameTable<EffectMeasure>& effect_measure_names();             ///< all, largest-posture
const NameTable<RefinementAllowance>& refinement_allowance_names(); ///< full, scaled

/// The name of `value` in `table`.
template <class E>
const std::string& name_of(const NameTable<E>& table, E value)
{
  for (const auto& [name, v] : table)
    if (v == value)
      return name;
  throw std::logic_error("rule value without a name");
}

/// The value named `name` in `table`; throws std::invalid_argument for an
/// unknown name (the command line checks the names first).
template <class E>
E value_of(const NameTable<E>& table, const std::string& name)
{
  for (const auto& [n, v] : table)
    if (n == name)
      return v;
  throw std::invalid_argument("unknown rule name '" + name + "'");
}

/// The names of `table`, in order.
template <class E>
std::vector<std::string> names_of(const NameTable<E>& table)
{
  std::vector<std::string> out;
  for (const auto& entry : table)
    out.push_back(entry.first);
  return out;
}
} // namespace breastsim::diagnosis
