// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The geometric checks of a user's mesh (src/mesh/user_mesh.hpp) once it is
// a TaggedMesh: units, cell volumes, curved cells, the faces against the
// tagged surfaces, the planes of base and symmetry, the half space.
#include "tagged_mesh.hpp"
#include <cstddef>
#include <string>
#include <vector>

namespace breastsim::meshes
{
/// What the messages name: the file, the gmsh element number of each cell
/// and facet of the TaggedMesh, the surfaces' tag values.
struct UserMeshOrigin
{
  std::string where;                        ///< "geometry.mesh_file = '<path>'"
  std::vector<std::size_t> cell_elements;   ///< gmsh element tag of each cell
  std::vector<std::size_t> facet_elements;  ///< gmsh element tag of each facet
  int base, skin, symmetry;                 ///< tag values of the surfaces
  bool half = true;                         ///< a half model (with "symmetry"); false: the full breast
};

/// Throw an InputError at the first failed check (user_mesh.hpp lists them).
void check_user_mesh(const TaggedMesh& m, const UserMeshOrigin& origin);
} // namespace breastsim::meshes
