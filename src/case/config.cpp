#include "config.hpp"
#include "breastsim_registry.hpp"
#include "errors.hpp"
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
constexpr double inf = std::numeric_limits<double>::infinity();

KeyInfo num(std::string key, std::string unit, double def, double lo, double hi, std::string doc,
            bool lo_open = false)
{
  KeyInfo k{std::move(key), KeyType::number, std::move(unit), def, lo, hi, lo_open, {},
            std::move(doc)};
  return k;
}

KeyInfo open_range(KeyInfo k)
{
  k.hi_open = true;
  return k;
}

KeyInfo integer(std::string key, std::int64_t def, double lo, double hi, std::string doc)
{
  return KeyInfo{std::move(key), KeyType::integer, "", def, lo, hi, false, {}, std::move(doc)};
}

KeyInfo boolean(std::string key, bool def, std::string doc)
{
  return KeyInfo{std::move(key), KeyType::boolean, "", def, -inf, inf, false, {}, std::move(doc)};
}

KeyInfo choice(std::string key, std::string def, std::vector<std::string> choices, std::string doc)
{
  return KeyInfo{std::move(key), KeyType::string, "", std::move(def), -inf, inf, false,
                 std::move(choices), std::move(doc)};
}

std::vector<KeyInfo> build_schema()
{
  std::vector<KeyInfo> s = {
      KeyInfo{"case.name", KeyType::string, "", std::string("breast"), -inf, inf, false, {},
              "name of the case (reports; default result folder results/<name>): a file-name "
              "component of 1 to 100 bytes, no '/', '\\', control characters, '.' or '..'"},
      num("geometry.R", "m", 0.07, 0.0, 0.5, "base radius of the neutral spherical cap", true),
      num("geometry.H", "m", 0.06, 0.0, 0.5,
          "height of the neutral cap (nipple at (0, H, 0)); at most 1.5 R", true),
      num("geometry.mesh_size", "m", 0.008, 0.0, 0.1,
          "target element size; between R/400 and min(R, H)/2", true),
      integer("geometry.order", 1, 1, 2, "element (and geometry) order: 1 = P1, 2 = P2"),
      integer("geometry.refinements", 0, 0, 4, "uniform refinements of the gmsh mesh"),
      boolean("base.fixed", false, "clamp the base (u = 0) instead of the spring bed"),
      num("gravity.g", "m/s^2", 9.81, 0.0, 100.0, "magnitude of gravity"),
      KeyInfo{"postures.names", KeyType::string_list, "",
              std::vector<std::string>{"standing", "supine", "all_fours"}, -inf, inf, false,
              {"standing", "supine", "all_fours", "prone"},
              "named postures to solve (standing: theta = 0, supine: 90, all_fours and "
              "prone: -90 deg)"},
      KeyInfo{"postures.theta_deg", KeyType::number_list, "deg", std::vector<double>{}, -180, 180,
              false, {}, "further postures by chest angle theta (SPEC.md), in [-180, 180]"},
      choice("solver.linear", "auto", {"auto", "direct", "amg"},
             "linear solver: direct (MUMPS LU), amg (GMRES + GAMG with rigid-body near "
             "nullspace), auto (direct up to solver.direct_max_dofs unknowns)"),
      choice("solver.amg_fine_smoother", "sor", {"sor", "chebyshev"},
             "smoother on the finest AMG level: sor (one symmetric Gauss-Seidel sweep) or "
             "chebyshev (GAMG's default Chebyshev/Jacobi; -mg_levels_* options then reach "
             "the finest level too)"),
      choice("solver.amg_cycle", "w", {"w", "v"},
             "multigrid cycle of the AMG preconditioner: w (coarse levels visited twice per "
             "level; fewer Krylov iterations on large meshes) or v"),
      integer("solver.direct_max_dofs", 20000, 0, 1e9,
              "largest problem solved directly by 'auto' (AMG is faster beyond, "
              "docs/PERFORMANCE.md)"),
      num("solver.rtol", "1", 1e-9, 0.0, 1e-2,
          "Newton tolerance on the residual norm relative to the full external load", true),
      num("solver.atol", "N", 1e-11, 0.0, 1.0, "absolute Newton tolerance on the residual norm"),
      boolean("solver.reuse_preconditioner", true,
              "keep the LU factors / AMG hierarchy of an earlier Jacobian while Krylov "
              "iterations stay few (rebuilt automatically)"),
      boolean("solver.inexact_newton", true,
              "solve each Newton system only to the Eisenstat-Walker tolerance (loose far "
              "from the solution, tight near it); false: to 1e-10 (direct) / 1e-8 (amg)"),
      num("solver.forcing_max", "1", 0.3, 0.0, 0.99,
          "loosest linear tolerance of the inexact Newton method", true),
      boolean("solver.coarse_start", true,
              "grid sequencing: solve each posture first on a coarse P1 mesh "
              "(solver.coarse_mesh_size; for P2 cases then on up to solver.nested_levels P2 "
              "meshes) and start Newton from the finest one's interpolant, when the mesh has at "
              "least 4x the coarse unknowns (docs/PERFORMANCE.md)"),
      num("solver.coarse_mesh_size", "m", 0.008, 0.0, 0.1,
          "mesh size of the coarse mesh of solver.coarse_start", true),
      num("solver.coarse_rtol", "1", 1e-6, 0.0, 1e-2,
          "Newton tolerance (relative to the load) of the coarse start's levels: they only "
          "provide the fine Newton's start", true),
      integer("solver.nested_levels", 2, 0, 4,
              "P2 cases with solver.coarse_start: at most this many intermediate P2 meshes "
              "between the coarse P1 mesh and the case's (mesh size doubled per level), each "
              "used when it has at least 4x the coarse unknowns"),
      integer("solver.max_iterations", 40, 1, 1000, "Newton iterations per load step"),
      num("solver.initial_load_step", "1", 1.0, 0.0, 1.0,
          "first load increment (fraction of the full load)", true),
      num("solver.min_load_step", "1", 1.0 / 1024, 0.0, 1.0,
          "smallest load increment before giving up", true),
      KeyInfo{"solver.petsc_options", KeyType::string, "", std::string(""), -inf, inf, false, {},
              "extra PETSc options, e.g. \"-ksp_type gmres -pc_type hypre\" (override ours)"},
      open_range(num("incision.a_deg", "deg", 30.0, 0.0, 90.0,
                     "surgery: angle a of plane P1 with the symmetry plane (90 deg would put "
                     "the plane into the symmetry plane)", true)),
      num("incision.s", "m", 0.02, 0.0, 0.5, "surgery: height s of the new nipple A above the base centre"),
      num("incision.h", "m", 0.025, 0.0, 0.5, "surgery: height y_D = h of point D above the base", true),
      num("incision.d", "m", 0.045, 0.0, 0.5, "surgery: depth of C = (0, 0, -d), the new inframammary fold"),
      num("surgery.max_gap", "m", 1e-4, 0.0, 0.01,
          "largest suture gap accepted (the penalty is raised until it is met)", true),
      num("solver.max_memory_gb", "GB", 0.0, 0.0, 1e6,
          "refuse a case whose estimated peak memory exceeds this (0: 80 % of this machine's "
          "memory); the estimate is in the message"),
      boolean("output.xdmf", true, "write displacement fields as XDMF (ParaView)"),
      boolean("output.vtk", false, "also write VTK files (native P2)"),
  };
  // Physics parameters and term switches generated from forms/.
  for (const auto& p : generated::parameters())
  {
    if (p.key.empty())
      continue;
    auto it = std::find_if(s.begin(), s.end(), [&](const KeyInfo& k) { return k.key == p.key; });
    if (it != s.end())
    {
      it->ufl_name = p.name; // a geometry key also bound into the forms
      continue;
    }
    KeyInfo k;
    k.key = p.key;
    k.unit = p.unit;
    k.lo = p.lo;
    k.hi = p.hi;
    k.lo_open = p.lo_open;
    k.doc = p.doc + " [term: " + p.term + "]";
    k.ufl_name = p.name;
    if (p.default_value.size() == 1)
    {
      k.type = KeyType::number;
      k.default_value = p.default_value[0];
    }
    else
    {
      k.type = KeyType::number_list;
      k.default_value = p.default_value;
      k.size = p.default_value.size();
    }
    s.push_back(k);
  }
  for (const auto& t : generated::terms())
    s.push_back(boolean("terms." + t.name, t.default_on, "switch the '" + t.name + "' energy term on/off"));
  return s;
}

} // namespace

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

namespace
{
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
    throw InputError(fmt::format("key '{}' = \"{}\" is not a number", key, s));
  return x;
}

std::vector<std::string> split(const std::string& s)
{
  std::vector<std::string> out;
  std::string item;
  std::istringstream is(s);
  while (std::getline(is, item, ','))
    if (!item.empty())
      out.push_back(item);
  return out;
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

const std::vector<KeyInfo>& schema()
{
  static const std::vector<KeyInfo> s = build_schema();
  return s;
}

const KeyInfo& key_info(const std::string& key)
{
  for (const auto& k : schema())
    if (k.key == key)
      return k;
  // Suggest keys of the same section.
  std::vector<std::string> near;
  const std::string section = key.substr(0, key.find('.'));
  for (const auto& k : schema())
    if (k.key.rfind(section + ".", 0) == 0)
      near.push_back(k.key);
  throw InputError(fmt::format("unknown key '{}'{}", key,
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

Config::Config()
{
  for (const auto& k : schema())
    _values[k.key] = k.default_value;
}

Config Config::from_file(const std::filesystem::path& path)
{
  if (!std::filesystem::exists(path))
    throw InputError(fmt::format("case file '{}' does not exist", path.string()));
  if (!std::filesystem::is_regular_file(path))
    throw InputError(fmt::format("case file '{}' is not a regular file (a folder?): give a "
                                 "TOML case file",
                                 path.string()));
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
      throw InputError(fmt::format("key '{}' = {} is not an integer", key, text));
    if (!(x >= k.lo && x <= k.hi)) // before the cast: 1e30 does not fit an int64
      throw InputError(fmt::format("key '{}' = {} is out of range: allowed {}", key, text,
                                   range_text(k)));
    set(key, static_cast<std::int64_t>(x));
    break;
  }
  case KeyType::boolean:
    if (text != "true" && text != "false")
      throw InputError(fmt::format("key '{}' = \"{}\": expected true or false", key, text));
    set(key, text == "true");
    break;
  case KeyType::string: set(key, text); break;
  case KeyType::number_list:
  {
    std::vector<double> xs;
    for (const auto& s : split(text))
      xs.push_back(parse_double(key, s));
    set(key, xs);
    break;
  }
  case KeyType::string_list: set(key, split(text)); break;
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
  const auto size = estimate_size(R, H, h, static_cast<int>(integer("geometry.order")),
                                  static_cast<int>(integer("geometry.refinements")));
  const double limit_gb = number("solver.max_memory_gb") > 0 ? number("solver.max_memory_gb")
                                                              : 0.8 * machine_memory_bytes() / 1e9;
  if (size.bytes > limit_gb * 1e9)
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
