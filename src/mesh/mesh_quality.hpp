// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Shape quality of a tetrahedral mesh (corner vertices of each cell).
#include <dolfinx/mesh/Mesh.h>
#include <nlohmann/json.hpp>

namespace breastsim
{
struct MeshQuality
{
  std::int64_t num_cells = 0;
  std::int64_t num_vertices = 0;
  double min_dihedral_deg = 0, max_dihedral_deg = 0;
  /// Radius ratio 3 r_in / r_circ (1 for the regular tetrahedron).
  double min_radius_ratio = 0, mean_radius_ratio = 0;
  double h_min = 0, h_max = 0; ///< shortest / longest edge [m]
};

/// Collective over the mesh communicator.
MeshQuality mesh_quality(const dolfinx::mesh::Mesh& mesh);
nlohmann::json to_json(const MeshQuality& q);
} // namespace breastsim
