// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// An incision (a, s, h, d) in the surgeon's terms and back (docs/CLINIC.md,
// "Plans in surgical terms"). The paper's two planes are the Wise
// (inverted-T) pattern: the keel between the symmetry plane and P1 is the
// vertical excision under the new nipple A, the lower pole beyond P2 the
// horizontal excision along the fold. Marked on the standing breast before
// surgery:
// - new nipple SN-N: the taut tape from the notch to A's standing position;
// - vertical limb: the skin's cut along P1 from A down to D, standing;
// - resection: the removed tissue's weight, rho x volume (full breast).
#include "incision.hpp"
#include "skin_measures.hpp"

namespace breastsim::clinic
{
struct SurgicalTerms
{
  double new_nipple_sn_n = 0; ///< [m]
  double vertical_limb = 0;   ///< [m]
  double resection_grams = 0; ///< [g], this breast
};

/// Resected volume of the incision on the neutral cap, full breast [m^3]:
/// over the half base disc, the length of each column y in [0, Y(x, z)]
/// that lies in the keel {n1 . p < c1} or beyond P2 {n2 . p < c2}
/// (midpoint rule on an n x n grid; P2's bound is linear in y).
double resected_volume(const HalfCapSpec& cap, const meshes::IncisionGeometry& g, int n = 600);

/// The incision in surgical terms on the pre-operative standing skin
/// `standing` (complete on rank 0; the result on every rank), with the notch
/// at `notch` in the breast's frame and the tissue density `rho`.
SurgicalTerms surgical_terms(const HalfCapSpec& cap, const IncisionSpec& in, const SkinSurface& standing,
                             const Point& notch, double rho, MPI_Comm comm);

/// The weights [g] a keel can remove with s, h, d of `in`: from the
/// narrowest (a = 1 deg) to the widest whose incision exists.
struct WeightRange
{
  double least = 0, most = 0, a_min = 0, a_max = 0;
};
/// Throws InputError when no incision exists at any angle.
WeightRange weight_range(const HalfCapSpec& cap, IncisionSpec in, double rho);

/// The angle a (deg) of P1 whose resection weighs `grams` with s, h, d of
/// `in` (bisection: a wider keel removes more; the keel dominates the
/// weight, the fold's depth d moves it by a few percent). Throws InputError
/// naming the weight and the range reachable with that s, h, d.
double angle_for_grams(const HalfCapSpec& cap, IncisionSpec in, double grams, double rho);

/// The neutral skin points of P1's cut from A down to D (x = (s - z) tan a
/// on the cap), n + 1 of them: the vertical limb.
std::vector<Point> limb_curve(const HalfCapSpec& cap, const IncisionSpec& in, int n = 120);

/// The neutral skin points of P2's cut from D out to the base rim at
/// z = -d, n + 1 of them: the upper edge of the horizontal excision.
std::vector<Point> p2_curve(const HalfCapSpec& cap, const IncisionSpec& in, int n = 40);

/// The Wise pattern as marked on the standing breast before surgery
/// (complete surface on the calling rank): both vertical limbs (A to D),
/// both arcs of P2 (D to the fold) and the fold's incision (the base rim
/// below z = -d, from one side through the lowest point to the other).
std::vector<std::vector<Point>> wise_marking(const HalfCapSpec& cap, const IncisionSpec& in,
                                             const SkinSurface& standing);
} // namespace breastsim::clinic
