#pragma once
// Case configuration: the documented key schema (fixed keys plus the physics
// parameters generated from forms/), TOML loading, --set overrides and
// validation. Input is checked here, once; messages name the key, the value
// and the allowed range.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <variant>
#include <vector>

namespace breastsim
{
using Value = std::variant<double, std::int64_t, bool, std::string, std::vector<double>,
                           std::vector<std::string>>;

enum class KeyType
{
  number,
  integer,
  boolean,
  string,
  number_list,
  string_list
};

struct KeyInfo
{
  std::string key;   ///< dotted key, e.g. "tissue.mu"
  KeyType type;
  std::string unit;
  Value default_value;
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  std::vector<std::string> choices; ///< allowed strings (string types)
  std::string doc;
  std::string ufl_name; ///< UFL Constant set from this key ("" if none)
  std::size_t size = 0; ///< fixed list length (0: any)
  bool hi_open = false; ///< upper bound excluded
};

/// All keys a case file may contain.
const std::vector<KeyInfo>& schema();
/// The schema entry of `key`; throws InputError naming the key if unknown.
const KeyInfo& key_info(const std::string& key);
/// Markdown table of every key (for `breastsim keys` and README).
std::string schema_markdown();
std::string type_name(KeyType t);
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
