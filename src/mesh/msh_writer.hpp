// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A TaggedMesh as a gmsh ASCII mesh file (format 2.2) with named physical
// groups: the volume "tissue" and the facet tags by name, so that the user
// mesh reader (user_mesh.hpp) reads it back as geometry.mesh_file.
#include "tagged_mesh.hpp"
#include <filesystem>
#include <map>
#include <string>

namespace breastsim::meshes
{
/// Write `m` (4- or 10-node tetrahedra in gmsh order) to `file`; the facets
/// of tag value v form the physical surface `facet_names.at(v)`. Throws
/// std::runtime_error when the file cannot be written.
void write_msh22(const TaggedMesh& m, const std::map<int, std::string>& facet_names,
                 const std::filesystem::path& file);
} // namespace breastsim::meshes
