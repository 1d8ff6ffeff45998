// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Helpers for a mixed (u, p) space W = V_u x Q whose first subspace is the
// blocked vector displacement. In dolfinx 0.5.2, W.sub({0, i}) of a blocked
// subelement collapses to the whole vector space, so a condition on one
// displacement component is built on W.sub({0}) with the pair of dof lists
// (W's, the collapsed space's) restricted to that component.
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <memory>
#include <petscsystypes.h>
#include <span>

namespace breastsim
{
/// u_i = 0 (component i = 0, 1, 2; all three for i = -1) on the dofs of the
/// facets `facets` (topological dimension 2) of the displacement W.sub({0}).
std::shared_ptr<const dolfinx::fem::DirichletBC<PetscScalar>>
mixed_displacement_bc(const dolfinx::fem::FunctionSpace& W, std::span<const std::int32_t> facets,
                      int component);
} // namespace breastsim
