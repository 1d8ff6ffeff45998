// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Nested uniform refinement of a tagged P1 tetrahedral mesh, without moving
// any node (verification): every tetrahedron is split into 8 by its
// edge midpoints (Bey's red refinement, inner octahedron cut along its
// shortest diagonal), every tagged boundary triangle into 4 with its tag. The
// domain is exactly the coarse polyhedron at every level and h halves
// exactly, as the MMS orders need (gmsh's own splitting snaps new boundary
// nodes to the CAD surfaces; docs/CONVERGENCE.md).
#include "tagged_mesh.hpp"

namespace breastsim
{
/// One red refinement of a P1 TaggedMesh (throws std::invalid_argument for P2).
meshes::TaggedMesh refine_red(const meshes::TaggedMesh& m);

/// The same P1 mesh as a 10-node (straight-sided) P2 mesh: one node at every
/// edge midpoint, gmsh node order (cells: edges 01, 12, 20, 30, 32, 31;
/// facets: 01, 12, 20).
meshes::TaggedMesh straight_p2(const meshes::TaggedMesh& m);

/// Move the nodes of the facets tagged `skin` onto the half cap's surface
/// (base radius R, height H), as gmsh's splitting does with new boundary
/// nodes: rim nodes (y = 0) radially in the base plane to radius R, the
/// others radially from the sphere's centre (0, H - Rs, 0) onto the sphere
/// (nodes on x = 0 stay there). Nodes already on it do not move.
void snap_to_cap(meshes::TaggedMesh& m, double R, double H, int skin);
} // namespace breastsim
