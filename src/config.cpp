#include "config.hpp"
#include "breastsim_registry.hpp"
#include "errors.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <sstream>
#include <toml++/toml.h>

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
              "name of the case (used in reports)"},
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
      num("incision.a_deg", "deg", 30.0, 0.0, 90.0,
          "surgery: angle a of plane P1 with the symmetry plane", true),
      num("incision.s", "m", 0.02, 0.0, 0.5, "surgery: height s of the new nipple A above the base centre"),
      num("incision.h", "m", 0.025, 0.0, 0.5, "surgery: height y_D = h of point D above the base", true),
      num("incision.d", "m", 0.045, 0.0, 0.5, "surgery: depth of C = (0, 0, -d), the new inframammary fold"),
      num("surgery.max_gap", "m", 1e-4, 0.0, 0.01,
          "largest suture gap accepted (the penalty is raised until it is met)", true),
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
  return fmt::format("{}{}, {}]", k.lo_open ? "(" : "[", k.lo, k.hi);
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
  if (std::isnan(x) || below || x > k.hi)
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

void flatten(const toml::table& t, const std::string& prefix, std::map<std::string, const toml::node*>& out)
{
  for (const auto& [k, v] : t)
  {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (auto* sub = v.as_table())
      flatten(*sub, key, out);
    else
      out[key] = &v;
  }
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
  toml::table t;
  try
  {
    t = toml::parse_file(path.string());
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
  // Group keys by section (sections in order of first appearance, keys in
  // schema order): a TOML table may only be opened once, and the schema
  // lists fixed keys (e.g. base.fixed) apart from physics keys (base.c).
  std::string out = "# Resolved breastsim configuration (every key, defaults included)\n";
  std::vector<std::string> sections;
  for (const auto& k : schema())
  {
    const std::string sec = k.key.substr(0, k.key.find('.'));
    if (std::find(sections.begin(), sections.end(), sec) == sections.end())
      sections.push_back(sec);
  }
  for (const auto& sec : sections)
  {
    out += "\n[" + sec + "]\n";
    for (const auto& k : schema())
    {
      if (k.key.substr(0, k.key.find('.')) != sec)
        continue;
      const Value& v = _values.at(k.key);
      std::string text = value_text(v);
      if (std::holds_alternative<double>(v))
        text = fmt::format("{:.17g}", std::get<double>(v));
      if (text.find_first_of(".eEin") == std::string::npos && std::holds_alternative<double>(v))
        text += ".0";
      out += k.key.substr(sec.size() + 1) + " = " + text + "\n";
    }
  }
  return out;
}
} // namespace breastsim
