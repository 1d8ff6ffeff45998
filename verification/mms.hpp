// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Method of manufactured solutions for the full energy (tissue + skin + base
// springs, gravity and sutures off): verification/forms/mms.py. On the half cap refined
// uniformly, solve R(u_h; v) = R(u_ex; v) for u_h and measure the L2 and H1
// errors against u_ex; the observed orders should be p + 1 and p for Pp.
#include "config.hpp"
#include "mesh_from_gmsh.hpp"
#include <dolfinx/fem/Constant.h>
#include <map>
#include <memory>
#include <petscsystypes.h>
#include <cstdint>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace breastsim
{
/// How the levels of an MMS study are meshed.
enum class MmsMeshes
{
  nested,      ///< gmsh P1 mesh of mesh_size, red-refined l times (nodes never move; P2:
               ///< straight 10-node cells): the coarse polyhedron at every level, h / 2^l
  gmsh_split,  ///< gmsh mesh of mesh_size split l times by gmsh (boundary nodes snapped
               ///< to the sphere), as geometry.refinements
  gmsh_remesh, ///< an independent gmsh mesh of mesh_size / 2^l (not nested)
  nested_snapped ///< nested, then the new skin nodes moved onto the sphere (as gmsh's
                 ///< splitting does; diagnosis of the split meshes)
};
/// "nested", "split", "remesh", "snapped"
MmsMeshes parse_mms_meshes(const std::string& name);
std::string to_string(MmsMeshes k);

struct MmsLevel
{
  int refinements = 0;
  std::int64_t cells = 0, dofs = 0;
  double h = 0;                 ///< largest cell diameter [m]
  double mesh_size = 0;         ///< gmsh target size of this level [m]
  double h_eff = 0;             ///< (cap volume / cells)^(1/3) [m]
  double error_l2 = 0;          ///< ||u_h - u_ex||_L2 [m^(5/2)]
  double error_h1 = 0;          ///< |u_h - u_ex|_H1 (seminorm)
  double rel_l2 = 0, rel_h1 = 0; ///< relative to ||u_ex||, |u_ex|_H1
  double min_dihedral_deg = 0; ///< mesh quality
  int newton_iterations = 0;
  double seconds = 0;
};

struct MmsStudy
{
  int order = 1;
  double mesh_size = 0;
  MmsMeshes meshes = MmsMeshes::nested;
  std::vector<MmsLevel> levels;
  /// Observed orders between consecutive levels,
  /// log(e_i / e_{i+1}) / log(h_eff_i / h_eff_{i+1}); one fewer than levels.
  std::vector<double> order_l2, order_h1;
};

/// The mesh of level `refinements` of the family `kind` from `mesh_size`
/// (the case's R and H; built on rank 0, distributed over comm).
TaggedDolfinxMesh mms_level_mesh(const Config& c, int order, double mesh_size, int refinements,
                                 MPI_Comm comm, MmsMeshes kind);

using MmsConstants = std::map<std::string, std::shared_ptr<dolfinx::fem::Constant<PetscScalar>>>;
/// Every UFL Constant of the model: registry defaults, then the case's
/// physics keys; on_tissue, on_skin, on_base_springs = 1, the other
/// switches 0; the plain membrane (skin_tension_only = 0).
MmsConstants mms_constants(const Config& c);

/// The material parameters of `c` (its physics keys; registry defaults
/// otherwise) with gravity, sutures and the tension-field relaxation off.
/// Geometry: the case's R and H; element order `order`; level `refinements`
/// of the mesh family `meshes` from `mesh_size`. Collective.
/// patch: the patch test instead (u_lin, a homogeneous deformation, solved
/// from u = 0; the errors must be round-off; rel_* still relative to u_ex).
MmsLevel solve_mms(const Config& c, int order, double mesh_size, int refinements, MPI_Comm comm,
                   bool patch = false, MmsMeshes meshes = MmsMeshes::gmsh_split);

/// solve_mms on levels l = 0 .. levels-1 of the mesh family `meshes`, and the
/// observed orders (h_eff = (V / cells)^(1/3): exactly h0 / 2^l when nested).
MmsStudy mms_study(const Config& c, int order, double mesh_size, int levels, MPI_Comm comm,
                   MmsMeshes meshes = MmsMeshes::nested);

nlohmann::json to_json(const MmsStudy& s);
/// Printable table: level, cells, dofs, h, L2, H1, orders.
std::string mms_table(const MmsStudy& s);
} // namespace breastsim
