#include "schema.hpp"
#include "breastsim_registry.hpp"
#include "errors.hpp"
#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>

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


/// The case, its geometry, gravity and postures.
std::vector<KeyInfo> case_keys()
{
  return {
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
  };
}

/// Newton, linear solver, grid sequencing and load stepping.
std::vector<KeyInfo> solver_keys()
{
  return {
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
  };
}

/// The incision and the sutures.
std::vector<KeyInfo> surgery_keys()
{
  return {
      open_range(num("incision.a_deg", "deg", 30.0, 0.0, 90.0,
                     "surgery: angle a of plane P1 with the symmetry plane (90 deg would put "
                     "the plane into the symmetry plane)", true)),
      num("incision.s", "m", 0.02, 0.0, 0.5, "surgery: height s of the new nipple A above the base centre"),
      num("incision.h", "m", 0.025, 0.0, 0.5, "surgery: height y_D = h of point D above the base", true),
      num("incision.d", "m", 0.045, 0.0, 0.5, "surgery: depth of C = (0, 0, -d), the new inframammary fold"),
      num("surgery.max_gap", "m", 1e-4, 0.0, 0.01,
          "largest suture gap accepted (the penalty is raised until it is met)", true),
  };
}

/// Resource limit and output formats.
std::vector<KeyInfo> output_keys()
{
  return {
      num("solver.max_memory_gb", "GB", 0.0, 0.0, 1e6,
          "refuse a case whose estimated peak memory exceeds this (0: 80 % of this machine's "
          "memory); the estimate is in the message"),
      boolean("output.xdmf", true, "write displacement fields as XDMF (ParaView)"),
      boolean("output.vtk", false, "also write VTK files (native P2)"),
  };
}

/// The physics parameters and term switches generated from forms/; a key
/// already declared above (a geometry key also bound into the forms) gets
/// its UFL name.
void add_generated_keys(std::vector<KeyInfo>& s)
{
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
}

std::vector<KeyInfo> build_schema()
{
  std::vector<KeyInfo> s;
  for (auto section : {case_keys, solver_keys, surgery_keys, output_keys})
  {
    auto keys = section();
    s.insert(s.end(), keys.begin(), keys.end());
  }
  add_generated_keys(s);
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
} // namespace breastsim
