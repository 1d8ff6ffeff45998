// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Case configuration: values for the keys of the schema (schema.hpp), TOML
// loading, --set overrides and validation. Input is checked here, once; messages name the key, the value
// and the allowed range.
#include "schema.hpp"
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace breastsim
{
/// A value as plain text: 30, 0.025, true, name (for labels and tables).
std::string plain_text(const Value& v);
/// Estimated tetrahedra and peak memory [bytes] of a case's mesh and solve.
struct SizeEstimate
{
  double cells = 0, bytes = 0;
};
SizeEstimate estimate_size(double R, double H, double mesh_size, int order, int refinements);

class Config
{
public:
  /// All defaults.
  Config();
  /// Defaults overridden by a TOML case file (validated).
  static Config from_file(const std::filesystem::path& path);
  /// Override one key from text (`--set key=value`), parsed by the key's type.
  void set_text(const std::string& key, const std::string& text);
  void set(const std::string& key, Value v);

  double number(const std::string& key) const;
  std::int64_t integer(const std::string& key) const;
  bool flag(const std::string& key) const;
  const std::string& text(const std::string& key) const;
  const std::vector<double>& numbers(const std::string& key) const;
  const std::vector<std::string>& strings(const std::string& key) const;

  /// Range and cross-key checks; throws InputError.
  void validate() const;
  nlohmann::json to_json() const;
  std::string to_toml() const;
  const std::map<std::string, Value>& values() const { return _values; }

private:
  std::map<std::string, Value> _values;
};
} // namespace breastsim
