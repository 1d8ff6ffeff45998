// SPDX-License-Identifier: LGPL-3.0-or-later
#include "config.hpp"
#include "strings.hpp"
#include "breastsim_registry.hpp"
#include "errors.hpp"
#include "input_file.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <sstream>
#include <toml++/toml.h>
#include <fstream>
#include <unistd.h>

namespace breastsim
{
namespace
{
void check_number(const KeyInfo& k, double x)
{
  const bool below = k.lo_open ? !(x > k.lo) : !(x >= k.lo);
  const bool above = k.hi_open ? !(x < k.hi) : !(x <= k.hi);
  if (std::isnan(x) || below || above)
    throw InputError(fmt::format("key '{}' = {} is out of range: allowed {} {}", k.key, x,
                                 range_text(k), k.unit));
}

/// Convert a TOML node to the key's type (integers are accepted as numbers).
Value from_toml(const KeyInfo& k, const toml::node& n)
{
  auto bad = [&]()
  {
    std::ostringstream os;
    n.visit([&](auto&& e) { os << e; });
    return InputError(fmt::format("key '{}' = {} has the wrong type: expected {}", k.key,
                                  os.str(), type_name(k.type)));
  };
  auto as_number = [&](const toml::node& e) -> double
  {
    if (auto d = e.value_exact<double>())
      return *d;
    if (auto i = e.value_exact<std::int64_t>())
      return static_cast<double>(*i);
    throw bad();
  };
  switch (k.type)
  {
  case KeyType::number: return as_number(n);
  case KeyType::integer:
    if (auto i = n.value_exact<std::int64_t>())
      return *i;
    throw bad();
  case KeyType::boolean:
    if (auto b = n.value_exact<bool>())
      return *b;
    throw bad();
  case KeyType::string:
    if (auto s = n.value_exact<std::string>())
      return *s;
    throw bad();
  case KeyType::number_list:
  {
    auto* a = n.as_array();
    if (!a)
      throw bad();
    std::vector<double> out;
    for (const auto& e : *a)
      out.push_back(as_number(e));
    return out;
  }
  case KeyType::string_list:
  {
    auto* a = n.as_array();
    if (!a)
      throw bad();
    std::vector<std::string> out;
    for (const auto& e : *a)
      if (auto s = e.value_exact<std::string>())
        out.push_back(*s);
      else
        throw bad();
    return out;
  }
  }
  throw bad();
}

constexpr int max_nesting = 16; // case keys are two levels deep

void flatten(const toml::table& t, const std::string& prefix, std::map<std::string, const toml::node*>& out,
             int depth = 0)
{
  for (const auto& [k, v] : t)
  {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (auto* sub = v.as_table())
    {
      if (depth + 1 >= max_nesting)
        throw InputError(fmt::format("unknown key '{}...': tables nested deeper than {} levels",
                                     key.substr(0, 60), max_nesting));
      flatten(*sub, key, out, depth + 1);
    }
    else
      out[key] = &v;
  }
}

/// Refuse text whose keys or brackets nest deeper than max_nesting before
/// toml++ parses it (its recursion overflows the stack on ~50,000 levels).
void check_nesting(const std::string& text, const std::filesystem::path& path)
{
  int line = 1, dots = 0, brackets = 0;
  bool in_key = true;
  char quote = 0;
  for (std::size_t i = 0; i < text.size(); ++i)
  {
    const char ch = text[i];
    if (ch == '\n')
    {
      ++line;
      dots = 0;
      in_key = brackets == 0;
      continue;
    }
    if (quote)
    {
      if (ch == '\\' && quote == '"')
        ++i;
      else if (ch == quote)
        quote = 0;
      continue;
    }
    if (ch == '"' || ch == '\'')
      quote = ch;
    else if (ch == '#')
      while (i + 1 < text.size() && text[i + 1] != '\n')
        ++i;
    else if (ch == '=')
      in_key = false;
    else if (ch == '.' && in_key)
      ++dots;
    else if ((ch == '[' || ch == '{') && !in_key)
      ++brackets;
    else if ((ch == ']' || ch == '}') && !in_key && brackets > 0)
      --brackets;
    if (dots >= max_nesting || brackets > max_nesting)
      throw InputError(fmt::format("case file '{}' line {}: {} nested deeper than {} levels "
                                   "(case keys are section.key)",
                                   path.string(), line, dots >= max_nesting ? "keys" : "values",
                                   max_nesting));
  }
}

/// case.name becomes a folder name: one safe path component.
void check_case_name(const std::string& name)
{
  auto bad = [&](const std::string& why)
  {
    std::string shown;
    for (unsigned char ch : name.substr(0, 60))
      shown += ch < 0x20 || ch == 0x7f ? fmt::format("\\x{:02x}", ch) : std::string(1, static_cast<char>(ch));
    return InputError(fmt::format("key 'case.name' = \"{}{}\" is not allowed: {} (allowed: 1 to 100 "
                                  "bytes, no '/', '\\', control characters, not '.' or '..')",
                                  shown, name.size() > 60 ? "..." : "", why));
  };
  if (name.empty())
    throw bad("it is empty");
  if (name.size() > 100)
    throw bad(fmt::format("it is {} bytes long", name.size()));
  if (name == "." || name == "..")
    throw bad("it names a folder of the path itself");
  for (unsigned char ch : name)
  {
    if (ch == '/' || ch == '\\')
      throw bad("it contains a path separator");
    if (ch < 0x20 || ch == 0x7f)
      throw bad("it contains a control character");
  }
}

template <typename T>
void check_unique(const std::string& key, const std::vector<T>& xs)
{
  for (std::size_t i = 0; i < xs.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (xs[i] == xs[j])
        throw InputError(fmt::format("key '{}' lists {} twice: each posture is solved once",
                                     key, value_text(Value(std::vector<T>{xs[i]}))));
}

double machine_memory_bytes()
{
  return static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
}

double parse_double(const std::string& key, const std::string& s)
{
  std::size_t pos = 0;
  double x = 0;
  try
  {
    x = std::stod(s, &pos);
  }
  catch (const std::exception&)
  {
    pos = 0;
  }
  if (pos != s.size() || s.empty())
    throw InputError(fmt::format("key '{}' = \"{}\" is not a number", key, shorten(s)));
  return x;
}

} // namespace

std::string plain_text(const Value& v)
{
  if (const auto* s = std::get_if<std::string>(&v))
    return *s;
  return value_text(v);
}

SizeEstimate estimate_size(double R, double H, double mesh_size, int order, int refinements)
{
  // Half cap of a sphere of radius Rs = (R^2 + H^2) / (2 H): V = pi H^2 (3 Rs - H) / 6.
  const double Rs = (R * R + H * H) / (2 * H);
  const double volume = M_PI * H * H * (3 * Rs - H) / 6;
  // gmsh's tetrahedra of size h: about 0.7 V / (h^3 / (6 sqrt 2)) (3174 measured for the
  // default case against 4755 regular ones), times 8 per uniform refinement.
  const double cells = 0.7 * volume / (std::pow(mesh_size, 3) / (6 * std::sqrt(2.0)))
                       * std::pow(8.0, refinements);
  // Peak RSS measured per cell (docs/PERFORMANCE.md): P1 ~ 6 kB, P2 ~ 11 kB, plus 150 MB.
  const double per_cell = order == 2 ? 11e3 : 6e3;
  return {cells, 150e6 + per_cell * cells};
}


Config::Config()
{
  for (const auto& k : schema())
    _values[k.key] = k.default_value;
}

namespace
{
/// A relative path of a case file, relative to the case file's folder.
std::string resolve_path(const std::string& value, const std::filesystem::path& case_file)
{
  if (value.empty() || std::filesystem::path(value).is_absolute())
    return value;
  return (case_file.parent_path() / value).lexically_normal().string();
}

/// Cross-key checks of a user mesh (geometry.mesh_file): the file exists,
/// and the mesh is not to be refined (solver.coarse_start is not used with
/// it: its levels are meshes of the parametric cap).
void check_user_mesh_keys(const Config& c)
{
  const std::string& file = c.text("geometry.mesh_file");
  if (file.empty())
  {
    if (c.number("geometry.nipple_z") != 0)
      throw InputError(fmt::format("key 'geometry.nipple_z' = {} needs geometry.mesh_file: the cap's "
                                   "nipple is at z = 0",
                                   c.number("geometry.nipple_z")));
    return;
  }
  if (!std::filesystem::is_regular_file(file))
    throw InputError(fmt::format("key 'geometry.mesh_file' = \"{}\": no such file", file));
  if (c.integer("geometry.refinements") != 0)
    throw InputError(fmt::format("key 'geometry.refinements' = {} with geometry.mesh_file: the user's "
                                 "mesh is used as it is; set geometry.refinements = 0",
                                 c.integer("geometry.refinements")));
  if (c.number("geometry.rim_size_ratio") != 1.0)
    throw InputError(fmt::format("key 'geometry.rim_size_ratio' = {} with geometry.mesh_file: the "
                                 "user's mesh keeps its own sizes; set geometry.rim_size_ratio = 1",
                                 c.number("geometry.rim_size_ratio")));
}
} // namespace

Config Config::from_file(const std::filesystem::path& path)
{
  check_input_file(path, "case file");
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof())
    throw InputError(fmt::format("case file '{}' cannot be read", path.string()));
  check_nesting(text, path);
  toml::table t;
  try
  {
    t = toml::parse(text, path.string());
  }
  catch (const toml::parse_error& e)
  {
    const auto& b = e.source().begin;
    throw InputError(fmt::format("case file '{}' is not valid TOML (line {}, column {}): {}",
                                 path.string(), b.line, b.column, e.description()));
  }
  Config c;
  std::map<std::string, const toml::node*> flat;
  flatten(t, "", flat);
  for (const auto& [key, node] : flat)
  {
    const KeyInfo& k = key_info(key);
    c._values[key] = from_toml(k, *node);
    if (k.path)
      c._values[key] = resolve_path(std::get<std::string>(c._values[key]), path);
  }
  c.validate();
  return c;
}

void Config::set(const std::string& key, Value v)
{
  const KeyInfo& k = key_info(key);
  if (v.index() != k.default_value.index())
  {
    if (k.type == KeyType::number && std::holds_alternative<std::int64_t>(v))
      v = static_cast<double>(std::get<std::int64_t>(v));
    else
      throw InputError(fmt::format("key '{}' = {} has the wrong type: expected {}", key,
                                   value_text(v), type_name(k.type)));
  }
  _values[key] = std::move(v);
}

void Config::set_text(const std::string& key, const std::string& text)
{
  const KeyInfo& k = key_info(key);
  switch (k.type)
  {
  case KeyType::number: set(key, parse_double(key, text)); break;
  case KeyType::integer:
  {
    const double x = parse_double(key, text);
    if (x != std::round(x))
      throw InputError(fmt::format("key '{}' = {} is not an integer", key, shorten(text)));
    if (!(x >= k.lo && x <= k.hi)) // before the cast: 1e30 does not fit an int64
      throw InputError(fmt::format("key '{}' = {} is out of range: allowed {}", key, shorten(text),
                                   range_text(k)));
    set(key, static_cast<std::int64_t>(x));
    break;
  }
  case KeyType::boolean:
    if (text != "true" && text != "false")
      throw InputError(fmt::format("key '{}' = \"{}\": expected true or false", key, shorten(text)));
    set(key, text == "true");
    break;
  case KeyType::string: set(key, text); break;
  case KeyType::number_list:
  {
    std::vector<double> xs;
    for (const auto& s : split_list(text))
      xs.push_back(parse_double(key, s));
    set(key, xs);
    break;
  }
  case KeyType::string_list: set(key, split_list(text)); break;
  }
}

double Config::number(const std::string& key) const { return std::get<double>(_values.at(key)); }
std::int64_t Config::integer(const std::string& key) const
{
  return std::get<std::int64_t>(_values.at(key));
}
bool Config::flag(const std::string& key) const { return std::get<bool>(_values.at(key)); }
const std::string& Config::text(const std::string& key) const
{
  return std::get<std::string>(_values.at(key));
}
const std::vector<double>& Config::numbers(const std::string& key) const
{
  return std::get<std::vector<double>>(_values.at(key));
}
const std::vector<std::string>& Config::strings(const std::string& key) const
{
  return std::get<std::vector<std::string>>(_values.at(key));
}

void Config::validate() const
{
  for (const auto& k : schema())
  {
    const Value& v = _values.at(k.key);
    switch (k.type)
    {
    case KeyType::number: check_number(k, std::get<double>(v)); break;
    case KeyType::integer: check_number(k, static_cast<double>(std::get<std::int64_t>(v))); break;
    case KeyType::number_list:
    {
      const auto& xs = std::get<std::vector<double>>(v);
      if (k.size && xs.size() != k.size)
        throw InputError(fmt::format("key '{}' = {} must have {} entries", k.key, value_text(v), k.size));
      for (double x : xs)
        check_number(k, x);
      break;
    }
    case KeyType::string:
      if (!k.choices.empty()
          && std::find(k.choices.begin(), k.choices.end(), std::get<std::string>(v)) == k.choices.end())
        throw InputError(fmt::format("key '{}' = {} is not allowed: {}", k.key, value_text(v), range_text(k)));
      break;
    case KeyType::string_list:
      for (const auto& s : std::get<std::vector<std::string>>(v))
        if (!k.choices.empty() && std::find(k.choices.begin(), k.choices.end(), s) == k.choices.end())
          throw InputError(fmt::format("key '{}' contains \"{}\": allowed {}", k.key, s, range_text(k)));
      break;
    case KeyType::boolean: break;
    }
  }
  // Cross-key checks.
  check_case_name(text("case.name"));
  check_unique("postures.names", strings("postures.names"));
  check_unique("postures.theta_deg", numbers("postures.theta_deg"));
  const double R = number("geometry.R"), H = number("geometry.H"), h = number("geometry.mesh_size");
  if (H > 1.5 * R)
    throw InputError(fmt::format("key 'geometry.H' = {} is out of range: allowed (0, 1.5 R] = (0, {:.6g}] m "
                                 "for geometry.R = {}", H, 1.5 * R, R));
  if (h > 0.5 * std::min(R, H) || h < R / 400)
    throw InputError(fmt::format("key 'geometry.mesh_size' = {} is out of range: allowed [R/400, "
                                 "min(R, H)/2] = [{:.6g}, {:.6g}] m", h, R / 400, 0.5 * std::min(R, H)));
  if (number("solver.min_load_step") > number("solver.initial_load_step"))
    throw InputError(fmt::format("key 'solver.min_load_step' = {} exceeds solver.initial_load_step = {}",
                                 number("solver.min_load_step"), number("solver.initial_load_step")));
  if (!flag("base.fixed") && !flag("terms.base_springs"))
    throw InputError("key 'terms.base_springs' = false with base.fixed = false leaves the base "
                     "held by nothing: set base.fixed = true (clamped base) or "
                     "terms.base_springs = true");
  if (!flag("base.fixed") && flag("terms.base_springs") && !(number("base.c") > 0))
    throw InputError(fmt::format("key 'base.c' = {} with base.fixed = false leaves the base held "
                                 "by nothing: give a positive spring stiffness or set base.fixed "
                                 "= true",
                                 number("base.c")));
  check_user_mesh_keys(*this);
  const auto size = estimate_size(R, H, h, static_cast<int>(integer("geometry.order")),
                                  static_cast<int>(integer("geometry.refinements")));
  const double limit_gb = number("solver.max_memory_gb") > 0 ? number("solver.max_memory_gb")
                                                              : 0.8 * machine_memory_bytes() / 1e9;
  if (text("geometry.mesh_file").empty() && size.bytes > limit_gb * 1e9)
    throw InputError(fmt::format("key 'geometry.mesh_size' = {} m (order {}, {} refinements) is "
                                 "too fine for this machine: about {:.3g} tetrahedra needing about "
                                 "{:.3g} GB, above the limit of {:.3g} GB (solver.max_memory_gb)",
                                 h, integer("geometry.order"), integer("geometry.refinements"),
                                 size.cells, size.bytes / 1e9, limit_gb));
  if (strings("postures.names").empty() && numbers("postures.theta_deg").empty())
    throw InputError("no posture requested: set postures.names and/or postures.theta_deg");
}

nlohmann::json Config::to_json() const
{
  nlohmann::json j;
  for (const auto& [key, v] : _values)
    std::visit([&](const auto& x) { j[key] = x; }, v);
  return j;
}

std::string Config::to_toml() const
{
  // toml++ writes (and escapes) every value; sections are tables.
  toml::table root;
  for (const auto& k : schema())
  {
    const std::string sec = k.key.substr(0, k.key.find('.'));
    const std::string name = k.key.substr(sec.size() + 1);
    if (!root.contains(sec))
      root.insert(sec, toml::table{});
    toml::table& t = *root[sec].as_table();
    std::visit(
        [&](const auto& x)
        {
          using X = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<X, std::vector<double>> || std::is_same_v<X, std::vector<std::string>>)
          {
            toml::array a;
            for (const auto& e : x)
              a.push_back(e);
            t.insert(name, std::move(a));
          }
          else
            t.insert(name, x);
        },
        _values.at(k.key));
  }
  std::ostringstream os;
  os << "# Resolved breastsim configuration (every key, defaults included)\n\n" << root << "\n";
  return os.str();
}
} // namespace breastsim
