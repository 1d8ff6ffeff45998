// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Conversion of a root-rank gmsh TaggedMesh into a distributed dolfinx mesh
// with its facet tags.
#include "tagged_mesh.hpp"
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/MeshTags.h>
#include <memory>
#include <mpi.h>
#include <vector>

namespace breastsim
{
/// A distributed mesh, its boundary facet tags and the element degree.
struct TaggedDolfinxMesh
{
  std::shared_ptr<dolfinx::mesh::Mesh> mesh;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> facets;
  int degree = 1;
};

/// The local facets tagged `value` (in the order of the tags).
std::vector<std::int32_t> tagged_facets(const dolfinx::mesh::MeshTags<std::int32_t>& tags, int value);

/// Distribute `m` (data on rank 0 only; `order` must agree on all ranks).
TaggedDolfinxMesh to_dolfinx(MPI_Comm comm, const meshes::TaggedMesh& m, int order);

/// Collective. The node coordinates of a mesh made by to_dolfinx, in the
/// numbering of its TaggedMesh (the input global indices), gathered on
/// rank 0 ((num_nodes, 3) row-major; empty on the other ranks).
std::vector<double> gather_geometry_nodes(const dolfinx::mesh::Mesh& mesh, std::size_t num_nodes);
} // namespace breastsim
