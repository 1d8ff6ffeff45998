// SPDX-License-Identifier: LGPL-3.0-or-later
#include "mixed_space.hpp"
#include <dolfinx/fem/Function.h>

namespace breastsim
{
using namespace dolfinx;

std::shared_ptr<const fem::DirichletBC<PetscScalar>>
mixed_displacement_bc(const fem::FunctionSpace& W, std::span<const std::int32_t> facets, int component)
{
  auto Wu = W.sub({0});
  auto Vu = std::make_shared<const fem::FunctionSpace>(Wu->collapse().first);
  auto zero = std::make_shared<const fem::Function<PetscScalar>>(Vu); // initialised to 0
  // Unrolled pairs (dof of W, dof of the blocked collapsed space = 3 node + component).
  auto dofs = fem::locate_dofs_topological({*Wu, *Vu}, 2, facets);
  const int bs = Vu->dofmap()->index_map_bs();
  std::array<std::vector<std::int32_t>, 2> kept;
  for (std::size_t k = 0; k < dofs[0].size(); ++k)
    if (component < 0 || dofs[1][k] % bs == component)
    {
      kept[0].push_back(dofs[0][k]);
      kept[1].push_back(dofs[1][k]);
    }
  return std::make_shared<const fem::DirichletBC<PetscScalar>>(zero, std::move(kept), Wu);
}
} // namespace breastsim
