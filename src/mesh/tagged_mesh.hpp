// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A tetrahedral mesh with tagged boundary facets, as produced by gmsh on the
// root rank (other ranks hold empty arrays). Node indices are 0-based and
// contiguous; cell and facet node orders are gmsh's.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace breastsim::meshes
{
struct TaggedMesh
{
  int order = 1;                           ///< geometry order (1: 4-node, 2: 10-node tets)
  std::vector<double> x;                   ///< node coordinates, row-major (n, 3)
  std::vector<std::int64_t> cells;         ///< (num_cells, 4 or 10), gmsh order
  std::vector<std::int64_t> facets;        ///< (num_facets, 3 or 6), gmsh order
  std::vector<std::int32_t> facet_tags;    ///< tag value of each facet
  std::size_t num_nodes() const { return x.size() / 3; }
  std::size_t nodes_per_cell() const { return order == 1 ? 4 : 10; }
  std::size_t nodes_per_facet() const { return order == 1 ? 3 : 6; }
  std::size_t num_cells() const { return cells.size() / nodes_per_cell(); }
};

/// RAII owner of the (process-global) gmsh library state.
class GmshSession
{
public:
  explicit GmshSession(bool verbose = false);
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

/// Mesh the current gmsh model (3D, element `order`, `refinements` uniform
/// splittings) and extract the tetrahedra of all volumes and the facets of
/// every 2D physical group (its tag = the group's tag).
TaggedMesh extract_tagged_mesh(int order, int refinements);
} // namespace breastsim::meshes
