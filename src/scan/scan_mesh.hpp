// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The tetrahedral mesh of a scanned breast: gmsh meshes the half ball
// |X| <= r_m, y >= 0 (with x >= 0 for a half model) and every node is moved
// radially onto the fitted skin,
//   x = (|X| / r_m) r(X / |X|) X / |X|,
// so the chest plane y = 0 stays the base, the plane x = 0 the symmetry face
// of a half model, and the sphere becomes the skin. The nipple's direction
// is a vertex of the geometry, so the nipple is a node of the skin.
#include "radial_fit.hpp"
#include "tagged_mesh.hpp"

namespace breastsim::scan
{
struct ScanMeshOptions
{
  double mesh_size = 0.006; ///< target element size [m] (build_scan_model: 0 = by the volume)
  int order = 1;            ///< 1: 4-node, 2: 10-node tetrahedra
  bool half = false;        ///< the half x >= 0 with a symmetry face
};

struct ScanMesh
{
  meshes::TaggedMesh mesh;
  Vec3 nipple{};       ///< the nipple node [m, breast frame]
  double volume = 0;   ///< of the tetrahedra [m^3] (the half with `half`)
};

/// Mesh the body under `skin` (breast frame); `nipple` is a skin point whose
/// direction becomes a node. Facets tagged base, skin, symmetry (half only).
/// InputError when a moved tetrahedron is inverted (the fit folds).
ScanMesh mesh_scan(const RadialSurface& skin, const Vec3& nipple, const ScanMeshOptions& o, int tag_base,
                   int tag_skin, int tag_symmetry);
} // namespace breastsim::scan
