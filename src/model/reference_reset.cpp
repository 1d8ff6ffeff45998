// SPDX-License-Identifier: LGPL-3.0-or-later
#include "reference_reset.hpp"
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/mesh/Topology.h>
#include <stdexcept>

namespace breastsim
{
std::vector<std::int32_t> node_dof_blocks(const Model& model)
{
  auto mesh = model.mesh().mesh;
  const auto& xdofs = mesh->geometry().dofmap();
  auto dofs = model.space()->dofmap();
  if (static_cast<std::size_t>(dofs->cell_dofs(0).size()) != xdofs.links(0).size())
    throw std::logic_error("node_dof_blocks: geometry and displacement degrees differ");
  // Both are Lagrange elements of the same degree and variant: local node i
  // of a cell is the same point for the geometry and for u. Ghost cells are
  // included so that every local node (shared ones too) is mapped.
  const std::int32_t ncells = mesh->topology().index_map(3)->size_local()
                              + mesh->topology().index_map(3)->num_ghosts();
  std::vector<std::int32_t> block(mesh->geometry().x().size() / 3, -1);
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    auto gn = xdofs.links(c);
    auto un = dofs->cell_dofs(c);
    for (std::size_t i = 0; i < gn.size(); ++i)
      block[gn[i]] = un[i];
  }
  return block;
}

void reset_reference(Model& model)
{
  std::span<double> x = model.mesh().mesh->geometry().x();
  auto u = model.displacement();
  const auto uu = u->x()->array();
  const std::vector<std::int32_t> block = node_dof_blocks(model);
  for (std::size_t n = 0; n < block.size(); ++n)
    for (int k = 0; k < 3 && block[n] >= 0; ++k)
      x[3 * n + k] += uu[3 * block[n] + k];
  u->x()->set(0.0);
}
} // namespace breastsim
