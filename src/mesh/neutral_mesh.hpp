// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The case's neutral (pre-operative) geometry: the half cap of geometry.R,
// geometry.H at the case's mesh size, order and refinements (HalfCapSpec),
// or the user's mesh of geometry.mesh_file.
#include "config.hpp"
#include "half_cap.hpp"
#include "mesh_from_gmsh.hpp"
#include <mpi.h>

namespace breastsim
{
/// Mesh the neutral half cap of the case (collective; gmsh runs on rank 0).
TaggedDolfinxMesh build_neutral_mesh(const Config& c, MPI_Comm comm);
} // namespace breastsim
