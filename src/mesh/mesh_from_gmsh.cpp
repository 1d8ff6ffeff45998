// SPDX-License-Identifier: LGPL-3.0-or-later
#include "mesh_from_gmsh.hpp"
#include "breastsim_registry.hpp"
#include <algorithm>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/CoordinateElement.h>
#include <dolfinx/fem/ElementDofLayout.h>
#include <dolfinx/graph/AdjacencyList.h>
#include <dolfinx/io/cells.h>
#include <dolfinx/io/xdmf_utils.h>
#include <dolfinx/mesh/cell_types.h>

namespace breastsim
{
std::vector<std::int32_t> tagged_facets(const dolfinx::mesh::MeshTags<std::int32_t>& tags, int value)
{
  std::vector<std::int32_t> out;
  for (std::size_t i = 0; i < tags.values().size(); ++i)
    if (tags.values()[i] == value)
      out.push_back(tags.indices()[i]);
  return out;
}

TaggedDolfinxMesh to_dolfinx(MPI_Comm comm, const meshes::TaggedMesh& m, int order)
{
  using namespace dolfinx;
  const int nodes_per_cell = order == 1 ? 4 : 10;
  // The coordinate element must be the one the compiled forms expect.
  auto factory = generated::function_space(order);
  if (!factory)
    throw std::runtime_error("element order " + std::to_string(order) + " is not compiled in");
  ufcx_function_space* space = factory("u");
  fem::CoordinateElement cmap(mesh::CellType::tetrahedron, space->geometry_degree,
                              static_cast<basix::element::lagrange_variant>(space->geometry_basix_variant));

  // Cells: gmsh node order -> dolfinx node order.
  const std::vector<std::uint8_t> perm = io::cells::perm_gmsh(mesh::CellType::tetrahedron, nodes_per_cell);
  const std::size_t nc = m.cells.size() / nodes_per_cell;
  std::vector<std::int64_t> cells(m.cells.size());
  for (std::size_t c = 0; c < nc; ++c)
    for (int j = 0; j < nodes_per_cell; ++j)
      cells[c * nodes_per_cell + j] = m.cells[c * nodes_per_cell + perm[j]];

  auto mesh = std::make_shared<mesh::Mesh>(mesh::create_mesh(
      comm, graph::regular_adjacency_list(std::move(cells), nodes_per_cell), cmap, m.x,
      {m.x.size() / 3, 3}, mesh::GhostMode::none));

  // Facets: distribute_entity_data expects, per facet, the nodes of the
  // closure of a cell facet in the coordinate-element layout; only the vertex
  // positions are read, so place the three corners there.
  const fem::ElementDofLayout layout = cmap.create_dof_layout();
  const std::vector<int>& closure = layout.entity_closure_dofs(2, 0);
  std::vector<std::size_t> vertex_pos;
  for (int v = 0; v < 4; ++v)
  {
    const int dof = layout.entity_dofs(0, v).front();
    if (auto it = std::find(closure.begin(), closure.end(), dof); it != closure.end())
      vertex_pos.push_back(std::distance(closure.begin(), it));
  }
  const std::size_t npf = m.order == 1 ? 3 : 6; // gmsh: corners first
  const std::size_t nf = m.facet_tags.size();
  std::vector<std::int64_t> entities(nf * closure.size());
  for (std::size_t f = 0; f < nf; ++f)
  {
    std::fill_n(entities.begin() + f * closure.size(), closure.size(), m.facets[f * npf]);
    for (std::size_t k = 0; k < vertex_pos.size(); ++k)
      entities[f * closure.size() + vertex_pos[k]] = m.facets[f * npf + k];
  }

  mesh->topology_mutable().create_entities(2);
  mesh->topology_mutable().create_connectivity(2, 3);
  auto [local, values] = io::xdmf_utils::distribute_entity_data(*mesh, 2, entities, m.facet_tags);
  auto adj = graph::regular_adjacency_list(std::move(local), 3);
  auto tags = std::make_shared<mesh::MeshTags<std::int32_t>>(
      mesh::create_meshtags(mesh, 2, adj, std::span<const std::int32_t>(values)));
  return {mesh, tags, order};
}

std::vector<double> gather_geometry_nodes(const dolfinx::mesh::Mesh& mesh, std::size_t num_nodes)
{
  // Each owned node as (input index, x, y, z), gathered and placed by index.
  const auto& g = mesh.geometry();
  const std::int32_t owned = g.index_map()->size_local();
  std::vector<double> mine;
  for (std::int32_t i = 0; i < owned; ++i)
    mine.insert(mine.end(), {static_cast<double>(g.input_global_indices()[i]), g.x()[3 * i],
                             g.x()[3 * i + 1], g.x()[3 * i + 2]});
  int rank, nranks;
  MPI_Comm_rank(mesh.comm(), &rank);
  MPI_Comm_size(mesh.comm(), &nranks);
  const int size = static_cast<int>(mine.size());
  std::vector<int> sizes(nranks), offsets(nranks, 0);
  MPI_Gather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, mesh.comm());
  for (int r = 1; r < nranks; ++r)
    offsets[r] = offsets[r - 1] + sizes[r - 1];
  std::vector<double> all(rank == 0 ? offsets.back() + sizes.back() : 0);
  MPI_Gatherv(mine.data(), size, MPI_DOUBLE, all.data(), sizes.data(), offsets.data(), MPI_DOUBLE, 0,
              mesh.comm());
  std::vector<double> x(rank == 0 ? 3 * num_nodes : 0);
  for (std::size_t k = 0; k + 3 < all.size(); k += 4)
    std::copy(&all[k + 1], &all[k + 4], &x[3 * static_cast<std::size_t>(all[k])]);
  return x;
}
} // namespace breastsim
