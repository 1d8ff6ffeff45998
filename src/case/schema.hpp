#pragma once
// The case-file key schema: every key with its type, unit, default, allowed
// range and meaning; fixed keys in sections (case and geometry, solver,
// surgery, output) plus the physics parameters and term switches generated
// from forms/.
#include <cstdint>
#include <limits>
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
/// The allowed values of a key in words: [lo, hi], one of ..., true or false.
std::string range_text(const KeyInfo& k);
/// A value as it is written in TOML (strings quoted, lists in brackets).
std::string value_text(const Value& v);
} // namespace breastsim
