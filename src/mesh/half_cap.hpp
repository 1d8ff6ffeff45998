// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Parametric half breast in its neutral state (docs/MODEL.md): the part x >= 0 of a
// spherical cap with base radius R in the plane y = 0 and apex (nipple) at
// (0, H, 0). Built with gmsh's OpenCASCADE kernel; split at z = 0 so that the
// apex is a mesh vertex.
#include "geometry_options.hpp"
#include "tagged_mesh.hpp"

namespace breastsim::meshes
{
/// R, H, mesh size, order and refinements (src/case/geometry_options.hpp).
using HalfCapSpec = breastsim::HalfCapSpec;

/// Radius of the sphere carrying the cap: Rs = (R^2 + H^2) / (2 H).
double sphere_radius(double R, double H);

/// Build the half cap in the current gmsh model, with physical surface groups
/// base / skin / symmetry tagged by `tag_base`, `tag_skin`, `tag_symmetry`.
void build_half_cap_geometry(const HalfCapSpec& spec, int tag_base, int tag_skin,
                             int tag_symmetry);

/// Generate the half cap and return its tagged mesh (call on one rank).
TaggedMesh mesh_half_cap(const HalfCapSpec& spec, int tag_base, int tag_skin,
                         int tag_symmetry);
} // namespace breastsim::meshes
