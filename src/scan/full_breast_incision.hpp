// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The incision (docs/MODEL.md "Incision", "Full breast and patient scans") on a
// full breast's own shape: the fitted skin r(d) d (radial_fit.hpp) in the
// breast frame (nipple on x = 0, chest y = 0, z cranial).
//   A = (0, y_A, s) on the skin; P1: x = (s - z) tan a and its mirror P1':
//   x = -(s - z) tan a; D (D') the skin point on P1 (P1') at y = h below A;
//   C = (0, 0, -d); P2 through C, parallel to e_x, through the height
//   z_P2 = (z_D + z_D') / 2 at y = h (D and D' differ on an asymmetric
//   breast: P2 meets the skin at y = h exactly only on a symmetric one);
//   B, B' = P1, P1' with P2 in y = 0.
// Resected: the keel {|x| < (s - z) tan a} and the lower pole beyond P2.
// The remaining body's cut faces: the keel faces on P1 (x > 0) and P1'
// (x < 0), the smaller of the two tagged suture_a (its nodes are sewn to
// their mirror images, which then lie, up to the skin's asymmetry, inside
// the other face, suture_b), and suture_bcd on P2.
#include "geometry_options.hpp"
#include "radial_fit.hpp"
#include "tagged_mesh.hpp"

namespace breastsim::scan
{
/// Points and planes; planes as n . p = c with n pointing into the remaining body.
struct FullIncisionGeometry
{
  Vec3 A, B, B_mirror, C, D, D_mirror;
  Vec3 n1, n1_mirror; ///< P1: n1 . p = c1 (kept side > c1), P1': n1_mirror . p = c1
  double c1 = 0;
  Vec3 n2;            ///< P2: n2 . p = c2, oriented towards A
  double c2 = 0;
  /// True if p lies in the keel or beyond P2.
  bool resected(const Vec3& p) const;
};

/// Construct the points and planes on `skin`. InputError naming the key
/// (incision.a_deg, .s, .h, .d), its value and the reason when a point does
/// not exist on this breast (A above the upper rim, D not on the skin below
/// A, C or B outside the base, A not on the kept side of P2).
FullIncisionGeometry full_incision_geometry(const RadialSurface& skin, const IncisionSpec& inc);

/// Facet tag values of the incised bodies' surfaces.
struct FullIncisionTags
{
  int base, skin, suture_a, suture_b, suture_bcd;
};

/// The meshes of the remaining body and of the resected tissue (gmsh, one
/// process), with their volumes from the CAD and that of the whole solid.
struct FullIncisionMeshes
{
  meshes::TaggedMesh kept, resected;
  double volume_solid = 0, volume_kept = 0, volume_resected = 0; ///< CAD [m^3]
  bool face_a_on_mirror = false; ///< suture_a is the keel face on P1' (x < 0), else on P1
};

/// Mesh both bodies at `mesh_size`, element `order`, `refinements`.
/// InputError when the cut removes everything or nothing, or misses a plane.
FullIncisionMeshes mesh_full_incision(const RadialSurface& skin, const FullIncisionGeometry& g,
                                      const FullIncisionTags& tags, double mesh_size, int order,
                                      int refinements);
} // namespace breastsim::scan
