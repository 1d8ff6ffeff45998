// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The fitted skin r(d) d (radial_fit.hpp) as an OpenCASCADE solid, so that
// the incision's booleans (planes) cut the breast's own shape: one cubic
// B-spline surface over the unit square mapped onto the disk of directions,
//   (p, q) = (u sqrt(1 - v^2 / 2), v sqrt(1 - u^2 / 2)),  u, v in [-1, 1],
// scaled to the disk of radius 1.06 (a little beyond the chest circle, so the
// surface reaches y < 0), interpolating r(p, q) d(p, q) at the Greville
// points of a uniform clamped knot vector; the chest plane y = 0 trims it
// (the body is the piece of the box y >= 0 under the surface) and is the
// planar base.
#include "radial_fit.hpp"
#include "tagged_mesh.hpp"

namespace breastsim::scan
{
/// Add the solid under `skin` to the current gmsh model (OCC; a GmshSession
/// must be open) with `grid` x `grid` control points. Returns its volume tag.
int add_skin_solid(const RadialSurface& skin, int grid = 31);

/// The skin of a tagged mesh fitted as scan-model fits a scan (degree 10,
/// smoothing 1e-7): every node of the facets tagged `tag_skin` (the base
/// rim included). `rms`: the RMS radial distance of those nodes to the fit.
RadialSurface fit_mesh_skin(const meshes::TaggedMesh& m, int tag_skin, double* rms = nullptr);
} // namespace breastsim::scan
