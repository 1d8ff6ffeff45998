// SPDX-License-Identifier: LGPL-3.0-or-later
#include "mixed_state.hpp"
#include "breastsim_mixed_registry.hpp"
#include "errors.hpp"
#include "mixed_space.hpp"
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/utils.h>
#include <fmt/format.h>

namespace breastsim
{
using namespace dolfinx;

std::string to_string(TissueFormulation f)
{
  return f == TissueFormulation::mixed ? "mixed" : "displacement";
}

MixedState::MixedState(const TaggedDolfinxMesh& mesh)
{
  if (mesh.degree != generated::mixed_degree())
    throw InputError(fmt::format("key 'tissue.formulation' = \"mixed\" is Taylor-Hood P{}-P{}: it "
                                 "needs geometry.order = {}, got {}", generated::mixed_degree(),
                                 generated::mixed_degree() - 1, generated::mixed_degree(), mesh.degree));
  _W = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(generated::mixed_function_space(), "w", mesh.mesh));
  _w = std::make_shared<fem::Function<T>>(_W);
  _w->name = "displacement_pressure";
  auto [V, map] = _W->sub({0})->collapse();
  _V = std::make_shared<fem::FunctionSpace>(std::move(V));
  _map = std::move(map);
}

void MixedState::pull(const fem::Function<T>& u)
{
  auto from = u.x()->array();
  auto to = _w->x()->mutable_array();
  const std::size_t n = std::min(_map.size(), from.size());
  for (std::size_t i = 0; i < n; ++i)
    to[_map[i]] = from[i];
  _w->x()->scatter_fwd();
}

void MixedState::push(fem::Function<T>& u) const
{
  auto from = _w->x()->array();
  auto to = u.x()->mutable_array();
  const std::size_t n = std::min(_map.size(), to.size());
  for (std::size_t i = 0; i < n; ++i)
    to[i] = from[_map[i]];
  u.x()->scatter_fwd();
}

std::vector<std::shared_ptr<const fem::DirichletBC<MixedState::T>>>
MixedState::bcs(const TaggedDolfinxMesh& mesh, bool symmetry, bool fixed_base) const
{
  std::vector<std::shared_ptr<const fem::DirichletBC<T>>> bcs;
  if (symmetry)
    bcs.push_back(mixed_displacement_bc(*_W, tagged_facets(*mesh.facets, generated::tag("symmetry")), 0));
  if (fixed_base)
    bcs.push_back(mixed_displacement_bc(*_W, tagged_facets(*mesh.facets, generated::tag("base")), -1));
  return bcs;
}

std::int64_t MixedState::num_dofs() const
{
  return _W->dofmap()->index_map->size_global() * _W->dofmap()->index_map_bs();
}
} // namespace breastsim
