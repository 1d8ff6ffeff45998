// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The incision of a breast reduction (docs/MODEL.md, "Incision") on the neutral
// half cap: points A, B, C, D and planes P1 ("ABD") and P2 ("BCD") from the
// parameters (a, s, h, d); the resected region; and the remeshed remaining
// body with its two cut faces tagged.
#include "half_cap.hpp"
#include <array>
#include <utility>
#include <vector>

namespace breastsim::meshes
{
using Point = std::array<double, 3>;

/// a, s, h, d (src/case/geometry_options.hpp).
using IncisionSpec = breastsim::IncisionSpec;

/// Points and planes of an incision on the cap (R, H). Planes as n . p = c
/// with n pointing into the remaining body.
struct IncisionGeometry
{
  Point A, B, C, D;
  Point n1; double c1; ///< P1: x cos a + (z - s) sin a = 0
  Point n2; double c2; ///< P2: through C and D, parallel to e_x
  /// True if p (reference frame) lies in the resected region:
  /// the keel {x < (s - z) tan a} or the far side of P2 from A.
  bool resected(const Point& p) const;
};

/// Construct A, B, C, D, P1, P2. Throws InputError naming the parameter when
/// a point does not exist on the cap or the cut is empty or everything.
IncisionGeometry incision_geometry(const HalfCapSpec& cap, const IncisionSpec& inc);

/// The half-space {n . p < c} (n unit) as an OCC box of size L (current gmsh model).
int half_space_box(const Point& n, double c, double L);

/// Physical group 1 of the OCC volumes `vols`; returns their CAD volume and
/// (in `faces`) the tags of their boundary faces (current gmsh model, synchronized).
double add_volume_group(const std::vector<std::pair<int, int>>& vols, std::vector<int>& faces);

/// gmsh's mesh options of the incised bodies: sizes in [mesh_size / 2, mesh_size], Delaunay, one thread.
void set_incision_mesh_options(double mesh_size);

/// Mesh the remaining body: physical surface groups base, skin, symmetry,
/// suture_abd (on P1) and suture_bcd (on P2) with the given tag values
/// {base, skin, symmetry, suture_abd, suture_bcd}. Also returns the remaining
/// (half-model) volume from the CAD.
TaggedMesh mesh_incised_cap(const HalfCapSpec& cap, const IncisionSpec& inc,
                            const std::array<int, 5>& tags, double* cad_volume = nullptr);

/// Mesh the resected part (the cap inside {n1 . p < c1} or {n2 . p < c2}, the
/// complement of the remaining body): physical surface groups as above (its
/// faces on P1 and P2 get the suture_abd / suture_bcd values). Also returns
/// its (half-model) volume from the CAD.
TaggedMesh mesh_resected_part(const HalfCapSpec& cap, const IncisionSpec& inc,
                              const std::array<int, 5>& tags, double* cad_volume = nullptr);
} // namespace breastsim::meshes
