// SPDX-License-Identifier: LGPL-3.0-or-later
#include "mms.hpp"
#include "mpi_sum.hpp"
#include "geometry_options.hpp"
#include "half_cap.hpp"
#include "breastsim_registry.hpp"
#include "errors.hpp"
#include "mesh_from_gmsh.hpp"
#include "mesh_quality.hpp"
#include "nested_mesh.hpp"
#include "residual_newton.hpp"
#include "timer.hpp"
#include "mms_p1.h"
#include "mms_p2.h"
#include <algorithm>
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/mesh/utils.h>
#include <fmt/format.h>
#include <numeric>
#include <petscksp.h>
#include <spdlog/spdlog.h>

namespace breastsim
{
using namespace dolfinx;
using T = PetscScalar;

namespace
{
struct MmsForms
{
  ufcx_form *residual, *jacobian, *error_l2, *error_h1, *norm_l2, *norm_h1;
  ufcx_function_space* (*space)(const char*);
  ufcx_expression* u_ex;
  ufcx_form *patch_residual, *patch_error_l2, *patch_error_h1;
};

MmsForms mms_forms(int order)
{
  if (order == 1)
    return {form_mms_p1_mms_residual, form_mms_p1_mms_jacobian, form_mms_p1_mms_error_l2,
            form_mms_p1_mms_error_h1, form_mms_p1_mms_norm_l2,  form_mms_p1_mms_norm_h1,
            functionspace_form_mms_p1_mms_residual, expression_mms_p1_u_ex,
            form_mms_p1_patch_residual, form_mms_p1_patch_error_l2, form_mms_p1_patch_error_h1};
  if (order == 2)
    return {form_mms_p2_mms_residual, form_mms_p2_mms_jacobian, form_mms_p2_mms_error_l2,
            form_mms_p2_mms_error_h1, form_mms_p2_mms_norm_l2,  form_mms_p2_mms_norm_h1,
            functionspace_form_mms_p2_mms_residual, expression_mms_p2_u_ex,
            form_mms_p2_patch_residual, form_mms_p2_patch_error_l2, form_mms_p2_patch_error_h1};
  throw InputError(fmt::format("MMS: element order {} is not compiled in (1, 2)", order));
}
} // namespace

MmsMeshes parse_mms_meshes(const std::string& name)
{
  if (name == "nested")
    return MmsMeshes::nested;
  if (name == "split")
    return MmsMeshes::gmsh_split;
  if (name == "remesh")
    return MmsMeshes::gmsh_remesh;
  if (name == "snapped")
    return MmsMeshes::nested_snapped;
  throw InputError(fmt::format("--mms-meshes: '{}' is not one of nested, split, remesh, snapped", name));
}

std::string to_string(MmsMeshes k)
{
  switch (k)
  {
  case MmsMeshes::nested:
    return "nested";
  case MmsMeshes::gmsh_split:
    return "split";
  case MmsMeshes::gmsh_remesh:
    return "remesh";
  default:
    return "snapped";
  }
}

/// The level's mesh: the case's half cap at the requested size and
/// refinement (built on rank 0, distributed over comm).
TaggedDolfinxMesh mms_level_mesh(const Config& c, int order, double mesh_size, int refinements,
                           MPI_Comm comm, MmsMeshes kind)
{
  const bool nested = kind == MmsMeshes::nested || kind == MmsMeshes::nested_snapped;
  HalfCapSpec spec = HalfCapSpec::from(c); // the case's R and H; the level's mesh below
  spec.mesh_size = kind == MmsMeshes::gmsh_remesh ? mesh_size / std::pow(2.0, refinements) : mesh_size;
  spec.order = nested ? 1 : order;
  spec.refinements = kind == MmsMeshes::gmsh_split ? refinements : 0;
  int rank;
  MPI_Comm_rank(comm, &rank);
  meshes::TaggedMesh tm;
  tm.order = order;
  if (rank == 0)
  {
    tm = meshes::mesh_half_cap(spec, generated::tag("base"), generated::tag("skin"), generated::tag("symmetry"));
    if (nested)
    {
      for (int l = 0; l < refinements; ++l)
      {
        tm = refine_red(tm);
        if (kind == MmsMeshes::nested_snapped)
          snap_to_cap(tm, spec.R, spec.H, generated::tag("skin"));
      }
      if (order == 2)
        tm = straight_p2(tm);
    }
  }
  return to_dolfinx(comm, tm, order);
}

/// The Constants of the forms: registry defaults, then the case's physics
/// keys; only tissue, skin and base springs on, and the plain membrane (the
/// relaxed tension-field energy is only C1).
MmsConstants mms_constants(const Config& c)
{
  MmsConstants constants;
  for (const auto& p : generated::parameters())
    constants[p.name] = std::make_shared<fem::Constant<T>>(std::span<const T>(p.default_value));
  for (const auto& k : schema())
  {
    if (k.ufl_name.empty() || !constants.count(k.ufl_name))
      continue;
    if (k.type == KeyType::number)
      constants[k.ufl_name]->value = {c.number(k.key)};
    else
      constants[k.ufl_name]->value = c.numbers(k.key);
  }
  for (const auto& t : generated::terms())
    constants["on_" + t.name] = std::make_shared<fem::Constant<T>>(
        (t.name == "tissue" || t.name == "skin" || t.name == "base_springs") ? 1.0 : 0.0);
  constants.at("skin_tension_only")->value = {0.0};
  return constants;
}

namespace
{
/// The forms of the MMS module on V, bound to u and the Constants; the
/// partner fields (forms/model.py) belong to terms that are off here: zero.
class MmsFormFactory
{
public:
  MmsFormFactory(std::shared_ptr<const fem::FunctionSpace> V, std::shared_ptr<fem::Function<T>> u,
                 const MmsConstants& constants, const TaggedDolfinxMesh& m)
      : _V(std::move(V)), _constants(constants.begin(), constants.end()), _mesh(m)
  {
    _coefficients = {{"u", u}};
    for (const auto& p : generated::partners())
      _coefficients[p.coefficient] = std::make_shared<fem::Function<T>>(_V);
  }
  std::shared_ptr<fem::Form<T>> operator()(ufcx_form* f, int rank) const
  {
    std::vector<std::shared_ptr<const fem::FunctionSpace>> spaces(rank, _V);
    return std::make_shared<fem::Form<T>>(fem::create_form<T>(
        *f, spaces, _coefficients, _constants,
        {{fem::IntegralType::exterior_facet, _mesh.facets.get()}}, _mesh.mesh));
  }

private:
  std::shared_ptr<const fem::FunctionSpace> _V;
  std::map<std::string, std::shared_ptr<const fem::Constant<T>>> _constants;
  std::map<std::string, std::shared_ptr<const fem::Function<T>>> _coefficients;
  const TaggedDolfinxMesh& _mesh;
};

/// Sliding symmetry u_x = 0 on x = 0 (u_ex satisfies it).
std::shared_ptr<const fem::DirichletBC<T>> symmetry_bc(const fem::FunctionSpace& V,
                                                       const TaggedDolfinxMesh& m)
{
  auto V0 = V.sub({0});
  const auto facets = tagged_facets(*m.facets, generated::tag("symmetry"));
  auto dofs = fem::locate_dofs_topological(*V0, 2, facets);
  return std::make_shared<const fem::DirichletBC<T>>(T(0), std::move(dofs), V0);
}

/// u = the interpolant of u_ex, with u_x = 0 exactly on the symmetry face.
void interpolate_exact(fem::Function<T>& u, const ufcx_expression& u_ex, const TaggedDolfinxMesh& m,
                       const std::vector<std::shared_ptr<const fem::DirichletBC<T>>>& bcs)
{
  auto e = fem::create_expression<T>(
      u_ex, std::map<std::string, std::shared_ptr<const fem::Function<T>>>{},
      std::map<std::string, std::shared_ptr<const fem::Constant<T>>>{}, m.mesh);
  u.interpolate(e);
  auto arr = u.x()->mutable_array();
  for (const auto& bc : bcs)
    bc->set(arr, 1.0);
  u.x()->scatter_fwd();
}

/// Newton until |R| <= 1e-11 |R0| (or stagnation at round-off below 1e-8
/// |R0|); the iterations, SolveError if |R| > 1e-8 |R0| at the end.
int converge(ResidualNewton& newton, double r0, int order, int refinements)
{
  ResidualNewtonOptions no;
  no.rtol = 1e-11;
  no.max_iterations = 30;
  no.max_halvings = 12;
  no.step_rtol = 1e-13;
  no.accept_rtol = 1e-8;
  const auto nr = newton.solve(r0, no, [&](int it, double r) {
    spdlog::debug("MMS P{} level {}: Newton {} |R| = {:.3e} (rel {:.3e})", order, refinements, it,
                  r, r / r0);
  });
  if (nr.lu_failed)
    throw SolveError(fmt::format("MMS P{} refinement {}: LU solve failed", order, refinements));
  if (!(nr.residual <= 1e-8 * r0))
    throw SolveError(fmt::format("MMS P{} refinement {}: Newton did not converge (|R|/|R0| = {:.3e})",
                                 order, refinements, nr.residual / r0));
  return nr.iterations;
}

/// The largest cell diameter over all ranks.
double largest_cell_diameter(const mesh::Mesh& mesh)
{
  const std::int32_t ncells = mesh.topology().index_map(3)->size_local();
  std::vector<std::int32_t> cells(ncells);
  std::iota(cells.begin(), cells.end(), 0);
  const auto hs = mesh::h(mesh, cells, 3);
  double local = hs.empty() ? 0.0 : *std::max_element(hs.begin(), hs.end()), global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, mesh.comm());
  return global;
}
} // namespace

MmsLevel solve_mms(const Config& c, int order, double mesh_size, int refinements, MPI_Comm comm,
                   bool patch, MmsMeshes kind)
{
  Stopwatch stopwatch("MMS level");
  const MmsForms uf = mms_forms(order);
  TaggedDolfinxMesh m = mms_level_mesh(c, order, mesh_size, refinements, comm, kind);
  auto V = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(uf.space, "u", m.mesh));
  auto u = std::make_shared<fem::Function<T>>(V);
  const MmsFormFactory create(V, u, mms_constants(c), m);
  const std::vector<std::shared_ptr<const fem::DirichletBC<T>>> bcs = {symmetry_bc(*V, m)};
  ResidualNewton newton(create(patch ? uf.patch_residual : uf.residual, 1), create(uf.jacobian, 2),
                        u, bcs);

  MmsLevel L;
  L.refinements = refinements;
  spdlog::debug("MMS P{} level {}: min dihedral angle {:.2f} deg", order, refinements,
                mesh_quality(*m.mesh).min_dihedral_deg);
  // Force scale: |R(0) - R(u_ex)| (u = 0: the full manufactured load).
  const double r0 = newton.residual_norm();
  // Newton from the interpolant of u_ex (from u = 0 the first iterates of
  // the membrane-dominated problem may invert elements); the converged
  // discrete solution does not depend on the initial guess. The patch test
  // starts from u = 0.
  if (!patch)
    interpolate_exact(*u, *uf.u_ex, m, bcs);
  L.newton_iterations = converge(newton, r0, order, refinements);

  auto scalar = [&](ufcx_form* f) { return mpi_sum(fem::assemble_scalar(*create(f, 0)), comm); };
  L.error_l2 = std::sqrt(scalar(patch ? uf.patch_error_l2 : uf.error_l2));
  L.error_h1 = std::sqrt(scalar(patch ? uf.patch_error_h1 : uf.error_h1));
  L.rel_l2 = L.error_l2 / std::sqrt(scalar(uf.norm_l2));
  L.rel_h1 = L.error_h1 / std::sqrt(scalar(uf.norm_h1));
  L.h = largest_cell_diameter(*m.mesh);
  L.cells = m.mesh->topology().index_map(3)->size_global();
  L.min_dihedral_deg = mesh_quality(*m.mesh).min_dihedral_deg;
  L.dofs = V->dofmap()->index_map->size_global() * V->dofmap()->index_map_bs();
  L.seconds = stopwatch.seconds();
  return L;
}

MmsStudy mms_study(const Config& c, int order, double mesh_size, int levels, MPI_Comm comm,
                   MmsMeshes kind)
{
  MmsStudy s;
  s.order = order;
  s.mesh_size = mesh_size;
  s.meshes = kind;
  const HalfCapSpec cap = HalfCapSpec::from(c);
  const double R = cap.R, H = cap.H;
  const double volume = M_PI * H * (3 * R * R + H * H) / 12; // the half cap
  for (int l = 0; l < levels; ++l)
  {
    const double hl = mesh_size / std::pow(2.0, l);
    s.levels.push_back(solve_mms(c, order, mesh_size, l, comm, false, kind));
    auto& L = s.levels.back();
    L.refinements = l;
    L.mesh_size = hl;
    L.h_eff = std::cbrt(volume / double(L.cells));
    spdlog::info("MMS P{} level {} (mesh_size {:g}): {} cells, {} dofs, L2 {:.4e}, H1 {:.4e} ({} "
                 "Newton, {:.1f} s)",
                 order, l, hl, L.cells, L.dofs, L.error_l2, L.error_h1, L.newton_iterations,
                 L.seconds);
  }
  for (std::size_t i = 0; i + 1 < s.levels.size(); ++i)
  {
    const double dh = std::log(s.levels[i].h_eff / s.levels[i + 1].h_eff);
    s.order_l2.push_back(std::log(s.levels[i].error_l2 / s.levels[i + 1].error_l2) / dh);
    s.order_h1.push_back(std::log(s.levels[i].error_h1 / s.levels[i + 1].error_h1) / dh);
  }
  return s;
}

nlohmann::json to_json(const MmsStudy& s)
{
  nlohmann::json j;
  j["element_order"] = s.order;
  j["mesh_size"] = s.mesh_size;
  j["meshes"] = to_string(s.meshes);
  j["expected_order_l2"] = s.order + 1;
  j["expected_order_h1"] = s.order;
  for (const auto& L : s.levels)
    j["levels"].push_back({{"level", L.refinements}, {"mesh_size", L.mesh_size},
                           {"cells", L.cells}, {"dofs", L.dofs}, {"h_max", L.h},
                           {"h_eff", L.h_eff}, {"min_dihedral_deg", L.min_dihedral_deg}, {"error_l2", L.error_l2}, {"error_h1", L.error_h1},
                           {"relative_error_l2", L.rel_l2}, {"relative_error_h1", L.rel_h1},
                           {"newton_iterations", L.newton_iterations}, {"seconds", L.seconds}});
  j["order_l2"] = s.order_l2;
  j["order_h1"] = s.order_h1;
  return j;
}

std::string mms_table(const MmsStudy& s)
{
  std::string out = fmt::format("MMS P{} ({} meshes from mesh_size {:g} m): expected orders L2 {}, H1 {}\n",
                                s.order, to_string(s.meshes), s.mesh_size, s.order + 1, s.order);
  out += fmt::format("{:>5} {:>8} {:>8} {:>10} {:>12} {:>12} {:>8} {:>8}\n", "level", "cells",
                     "dofs", "h_eff[mm]", "L2 error", "H1 error", "p(L2)", "p(H1)");
  for (std::size_t i = 0; i < s.levels.size(); ++i)
  {
    const auto& L = s.levels[i];
    std::string pl = i ? fmt::format("{:.3f}", s.order_l2[i - 1]) : "-";
    std::string ph = i ? fmt::format("{:.3f}", s.order_h1[i - 1]) : "-";
    out += fmt::format("{:>5} {:>8} {:>8} {:>10.3f} {:>12.4e} {:>12.4e} {:>8} {:>8}\n",
                       L.refinements, L.cells, L.dofs, 1e3 * L.h_eff, L.error_l2, L.error_h1, pl, ph);
  }
  return out;
}
} // namespace breastsim
