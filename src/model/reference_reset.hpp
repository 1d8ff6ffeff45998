// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The final neutral state (docs/MODEL.md): the current deformed configuration
// becomes the new stress-free reference. The mesh geometry is moved by the
// displacement and u is set to zero.
#include "model.hpp"
#include <cstdint>
#include <vector>

namespace breastsim
{
/// The displacement dof block (u dofs 3 b .. 3 b + 2) at each local geometry
/// node (owned and ghost), -1 where none.
std::vector<std::int32_t> node_dof_blocks(const Model& model);

/// x_geometry += u at every geometry node, then u = 0 (collective).
/// Requires the isoparametric setting (geometry and displacement elements of
/// the same degree, as the compiled forms are).
void reset_reference(Model& model);
} // namespace breastsim
