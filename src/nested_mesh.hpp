#pragma once
// Nested uniform refinement of a tagged P1 tetrahedral mesh, without moving
// any node (issue 5, verification): every tetrahedron is split into 8 by its
// edge midpoints (Bey's red refinement, inner octahedron cut along its
// shortest diagonal), every tagged boundary triangle into 4 with its tag. The
// domain is exactly the coarse polyhedron at every level and h halves
// exactly, as the MMS orders need (gmsh's own splitting snaps new boundary
// nodes to the CAD surfaces; docs/CONVERGENCE.md).
#include "../meshes/tagged_mesh.hpp"

namespace breastsim
{
/// One red refinement of a P1 TaggedMesh (throws std::invalid_argument for P2).
meshes::TaggedMesh refine_red(const meshes::TaggedMesh& m);

/// The same P1 mesh as a 10-node (straight-sided) P2 mesh: one node at every
/// edge midpoint, gmsh node order (cells: edges 01, 12, 20, 30, 32, 31;
/// facets: 01, 12, 20).
meshes::TaggedMesh straight_p2(const meshes::TaggedMesh& m);
} // namespace breastsim
