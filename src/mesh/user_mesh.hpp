// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A user's tetrahedral gmsh mesh (.msh of format 2.2 or 4.x, 4-node or
// 10-node tetrahedra) as the neutral geometry, in the frame of docs/MODEL.md:
// metres, the chest is the plane y = 0 and the body lies in y >= 0, the half
// model lies in x >= 0 with its symmetry face on x = 0.
//
// Physical groups, found by name:
//   volume  "tissue"    the tetrahedra of the body;
//   surface "base"      the attachment to the chest, on the plane y = 0;
//   surface "skin"      the outer surface;
//   surface "symmetry"  the cut face of a half model, on the plane x = 0.
// Every boundary face of the tetrahedra belongs to exactly one of the
// surfaces. Without a "symmetry" group the mesh is the full breast (x of
// either sign, no sliding condition; docs/MODEL.md "Geometry"); with it, the
// half x >= 0, whose observables (volume, energy, base perimeter) mirror it.
//
// Checked on read, each failure an InputError naming geometry.mesh_file, the
// group and the cell or node: the file (exists, starts with $MeshFormat: a
// gmsh script is never run), the groups (present, of the right dimension),
// the cells (tetrahedra of the case's order, triangles on the surfaces),
// positive volumes (signed corner volume > 1e-8 (longest edge)^3; for
// 10-node tetrahedra also det J > 0 at the ten nodes), the faces (each tagged
// triangle is a boundary face of one tetrahedron, each boundary face is
// tagged once), the planes (base on y = 0 facing -y, symmetry on x = 0
// facing -x, the body in y >= 0 and, for a half model, x >= 0) and the units
// (extent < 1 m).
#include "mesh_from_gmsh.hpp"
#include "tagged_mesh.hpp"
#include <array>
#include <filesystem>
#include <optional>
#include <mpi.h>

namespace breastsim::meshes
{
/// Facet tag values given to the surfaces read (the registry's TAGS).
struct UserMeshTags
{
  int base, skin, symmetry;
};

/// Read and check the mesh file `path` (on one rank; opens its own gmsh
/// session). Its tetrahedra must be of `order` (the case's geometry.order).
TaggedMesh read_user_mesh(const std::filesystem::path& path, int order, const UserMeshTags& tags);
} // namespace breastsim::meshes

namespace breastsim
{
/// The skin node of `m` at `nipple` (within 1e-6 of the mesh's extent; one
/// rank); InputError naming `path` and the highest node on x = 0 if none.
std::size_t nipple_node(const meshes::TaggedMesh& m, const std::filesystem::path& path,
                        const std::array<double, 3>& nipple);

/// Collective: rank 0 reads `path` (read_user_mesh with the registry's tags
/// base, skin, symmetry), every rank throws its InputError, and the mesh is
/// distributed as build_neutral_mesh's half cap is. With `nipple`, the point
/// where the observables are read must be a skin node (within 1e-6 of the
/// mesh's extent): else an InputError names the highest node on x = 0.
TaggedDolfinxMesh load_user_mesh(const std::filesystem::path& path, int order, MPI_Comm comm,
                                 const std::optional<std::array<double, 3>>& nipple = std::nullopt);
} // namespace breastsim
