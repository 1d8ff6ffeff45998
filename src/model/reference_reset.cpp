#include "reference_reset.hpp"
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/mesh/Topology.h>

namespace breastsim
{
void reset_reference(Model& model)
{
  auto mesh = model.mesh().mesh;
  auto u = model.displacement();
  auto V = model.space();
  auto& geom = mesh->geometry();
  const auto& xdofs = geom.dofmap();
  auto dofs = V->dofmap();
  std::span<double> x = mesh->geometry().x();
  auto uu = u->x()->array();
  if (static_cast<std::size_t>(dofs->cell_dofs(0).size()) != xdofs.links(0).size())
    throw std::logic_error("reset_reference: geometry and displacement degrees differ");
  // Both are Lagrange elements of the same degree and variant: local node i
  // of a cell is the same point for the geometry and for u. Ghost cells are
  // included so that shared nodes move identically on every rank.
  const std::int32_t ncells = mesh->topology().index_map(3)->size_local()
                              + mesh->topology().index_map(3)->num_ghosts();
  std::vector<char> moved(x.size() / 3, 0);
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    auto gn = xdofs.links(c);
    auto un = dofs->cell_dofs(c);
    for (std::size_t i = 0; i < gn.size(); ++i)
    {
      if (moved[gn[i]])
        continue;
      moved[gn[i]] = 1;
      for (int k = 0; k < 3; ++k)
        x[3 * gn[i] + k] += uu[3 * un[i] + k];
    }
  }
  u->x()->set(0.0);
}
} // namespace breastsim
