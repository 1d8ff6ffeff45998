// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The case-file key schema: every key with its type, unit, default, allowed
// range and meaning; the fixed keys declared by the option structs of their
// sections (case_options, solver_options, surgery_options, output_options),
// then the physics parameters and term switches generated from forms/.
// schema() is composed in case_schema.cpp, a unit of its own: the option
// structs parse a Config, and Config reads the schema.
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
  /// A file path: a relative value in a case file is taken relative to the
  /// case file's folder (relative --set values: to the working directory).
  bool path = false;
};

/// All keys a case file may contain (composed in case_schema.cpp).
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

/// Schema entries, for the option structs' declare(): a number in [lo, hi]
/// ((lo, hi] with lo_open), an integer in [lo, hi], a boolean, a string from
/// `choices`, a free string.
KeyInfo number_key(std::string key, std::string unit, double def, double lo, double hi,
                   std::string doc, bool lo_open = false);
KeyInfo integer_key(std::string key, std::int64_t def, double lo, double hi, std::string doc);
KeyInfo boolean_key(std::string key, bool def, std::string doc);
KeyInfo choice_key(std::string key, std::string def, std::vector<std::string> choices,
                   std::string doc);
KeyInfo text_key(std::string key, std::string def, std::string doc);
/// The same entry with its upper bound excluded: [lo, hi) or (lo, hi).
KeyInfo upper_bound_open(KeyInfo k);
} // namespace breastsim
