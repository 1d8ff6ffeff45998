// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Clinical tape measures on the deformed skin of a half model (SPEC frame:
// base centre at the origin, chest y = 0, z up, symmetry plane x = 0 through
// the nipple; docs/CLINIC.md, "Definitions"):
// - the meridian: the skin's boundary curve in the symmetry plane, from the
//   nipple up and down to where it leaves that plane at the chest (the base
//   rim, or after surgery D, sewn to the chest); its lower end is the
//   inframammary fold (IMF);
// - N-IMF: the length along the skin of the meridian from the nipple to the fold;
// - SN-N: a taut tape from the sternal notch (a point of the chest plane)
//   to the nipple, in the vertical plane through both (normal to the chest):
//   the upper convex envelope of the skin's profile in that plane;
// - base width: twice the largest |x| of the skin's chest-side rim.
#include "surface_export.hpp"
#include <array>
#include <vector>

namespace breastsim::clinic
{
using Point = std::array<double, 3>;

/// The meridian of a half model's skin, as deformed: points from the upper
/// chest end through the nipple to the fold, and the index of the vertex
/// nearest the nipple. `plane_tolerance` [m]: a boundary vertex whose
/// reference |x| is at most this lies in the symmetry plane (after surgery
/// the keel's skin edge is sewn to it within the suture's gap).
struct Meridian
{
  std::vector<Point> points;
  std::size_t nipple = 0;
};
/// Throws InputError if `s` is not a half model or its boundary does not
/// form one loop through the nipple.
Meridian skin_meridian(const SkinSurface& s, const Point& nipple, double plane_tolerance = 2e-4);

/// Length of the polyline `p` from its vertex `from` to its last vertex.
double arc_length(const std::vector<Point>& p, std::size_t from);

/// Length of the skin from the nipple to the fold along the meridian [m]
/// (N-IMF); `fold` receives the fold's deformed position, `path` the
/// tape's points from the nipple to the fold.
double nipple_to_fold(const SkinSurface& s, const Point& nipple, Point* fold = nullptr,
                      std::vector<Point>* path = nullptr);

/// Outermost skin height y over the chest point (x, z) of the deformed skin
/// (a half model mirrored to x < 0); 0 where the skin does not cover it.
double skin_height(const SkinSurface& s, double x, double z);

/// A taut tape from the chest point `notch` = (x, 0, z) to the skin point
/// `nipple` over the chest and the skin (SN-N) [m], sampled every `step` [m];
/// `path` receives the tape's corners from the notch to the nipple.
double taut_tape(const SkinSurface& s, const Point& notch, const Point& nipple, double step = 5e-4,
                 std::vector<Point>* path = nullptr);

/// Width of the breast's base: twice the largest |x| of the deformed skin
/// vertices whose reference lies on the chest [m].
double base_width(const SkinSurface& s, double chest_tolerance = 2e-4);

/// |a - b| [m].
double distance(const Point& a, const Point& b);

/// l0 a + l1 b + l2 c: the point of barycentric coordinates l in (a, b, c).
Point barycentric_point(const std::array<double, 3>& l, const Point& a, const Point& b, const Point& c);

/// Barycentric coordinates of the point of triangle (a, b, c) closest to p
/// (Ericson, Real-Time Collision Detection, 5.1.5).
std::array<double, 3> closest_barycentric(const Point& p, const Point& a, const Point& b, const Point& c);

/// The deformed position of the reference skin point nearest `reference`:
/// its closest point on the reference skin, carried by the barycentric
/// coordinates of its triangle.
Point deformed_position(const SkinSurface& s, const Point& reference);

/// The skin surface of a surface document (surface_json(): vertices_ref,
/// vertices, triangles, mirror_x).
SkinSurface skin_surface(const nlohmann::json& doc);

/// Regnault's ptosis grade from the nipple's height below the fold [m]
/// (negative: above it): 0 more than 1 cm above, 1 within 1 cm of the
/// fold's level, 2 1-3 cm below, 3 more than 3 cm below.
int ptosis_grade(double nipple_below_fold);
} // namespace breastsim::clinic
