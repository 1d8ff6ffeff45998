// SPDX-License-Identifier: LGPL-3.0-or-later
// The incision on a full breast's own shape (src/scan/full_breast_incision,
// src/scan/skin_solid): on a hemisphere (r(d) = R, the cap with H = R) the
// points equal the half cap's incision (src/mesh/incision) and their mirror
// images, the OCC solid has the hemisphere's volume, the remaining body is
// twice the half cap's, and impossible plans are refused by key.
#include "errors.hpp"
#include "full_breast_incision.hpp"
#include "incision.hpp"
#include "skin_solid.hpp"
#include <algorithm>
#include <cmath>
#include <gmsh.h>
#include <gtest/gtest.h>

using namespace breastsim;

namespace
{
constexpr double R = 0.06;

scan::RadialSurface hemisphere() { return {0, {R}}; }

HalfCapSpec cap(double mesh_size)
{
  HalfCapSpec c;
  c.R = c.H = R;
  c.mesh_size = mesh_size;
  return c;
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

/// The message of the InputError that f throws ("" if none).
template <typename F>
std::string refusal(F f)
{
  try
  {
    f();
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST(FullBreastIncision, SkinSolidOfAHemisphereHasItsVolume)
{
  meshes::GmshSession session;
  const int body = scan::add_skin_solid(hemisphere());
  double volume;
  gmsh::model::occ::getMass(3, body, volume);
  EXPECT_NEAR(volume / (2 * M_PI * R * R * R / 3), 1.0, 1e-3);
}

TEST(FullBreastIncision, PointsOnAHemisphereAreTheHalfCapsAndTheirMirrors)
{
  const IncisionSpec inc; // a = 30 deg, s = 20 mm, h = 25 mm, d = 45 mm
  const auto full = scan::full_incision_geometry(hemisphere(), inc);
  const auto half = meshes::incision_geometry(cap(0.01), inc);
  EXPECT_LT(distance(full.A, half.A), 1e-9);
  EXPECT_LT(distance(full.B, half.B), 1e-12);
  EXPECT_LT(distance(full.C, half.C), 1e-12);
  EXPECT_LT(distance(full.D, half.D), 1e-9);
  EXPECT_LT(distance(full.D_mirror, {-half.D[0], half.D[1], half.D[2]}), 1e-9);
  EXPECT_LT(distance(full.B_mirror, {-half.B[0], half.B[1], half.B[2]}), 1e-12);
  EXPECT_LT(distance(full.n2, half.n2), 1e-9); // P2 through C and D = D' mirrored
  EXPECT_TRUE(full.resected({0.0, 0.01, 0.0}));  // inside the keel
  EXPECT_FALSE(full.resected({0.0, 0.01, 0.03})); // above A
}

TEST(FullBreastIncision, RemainingBodyIsTwiceTheHalfCaps)
{
  const IncisionSpec inc;
  const auto g = scan::full_incision_geometry(hemisphere(), inc);
  const scan::FullIncisionTags tags{1, 2, 6, 7, 5};
  const auto meshes = scan::mesh_full_incision(hemisphere(), g, tags, 0.015, 1, 0);
  double half_kept = 0, half_resected = 0;
  meshes::mesh_incised_cap(cap(0.015), inc, {1, 2, 3, 4, 5}, &half_kept);
  meshes::mesh_resected_part(cap(0.015), inc, {1, 2, 3, 4, 5}, &half_resected);
  EXPECT_NEAR(meshes.volume_kept / (2 * half_kept), 1.0, 2e-3);
  EXPECT_NEAR(meshes.volume_resected / (2 * half_resected), 1.0, 2e-3);
  // OCC integrates the volumes of B-spline-bounded bodies to about 3e-4
  EXPECT_NEAR((meshes.volume_kept + meshes.volume_resected) / meshes.volume_solid, 1.0, 1e-3);
  for (int tag : {1, 2, 5, 6, 7}) // base, skin, suture_bcd, suture_a, suture_b
    EXPECT_GT(std::count(meshes.kept.facet_tags.begin(), meshes.kept.facet_tags.end(), tag), 0) << tag;
}

TEST(FullBreastIncision, ImpossiblePlansAreRefusedByKey)
{
  auto plan = [](double a, double s, double h, double d)
  { return refusal([&] { scan::full_incision_geometry(hemisphere(), IncisionSpec{a, s, h, d}); }); };
  EXPECT_NE(plan(30, 0.07, 0.025, 0.045).find("'incision.s' = 0.07"), std::string::npos);
  EXPECT_NE(plan(30, 0.02, 0.058, 0.045).find("'incision.h' = 0.058"), std::string::npos);
  EXPECT_NE(plan(30, 0.02, 0.025, 0.07).find("'incision.d' = 0.07"), std::string::npos);
  EXPECT_NE(plan(80, 0.02, 0.025, 0.045).find("'incision.a_deg' = 80"), std::string::npos);
  EXPECT_NE(plan(95, 0.02, 0.025, 0.045).find("'incision.a_deg' = 95"), std::string::npos);
  EXPECT_EQ(plan(30, 0.02, 0.025, 0.045), "");
}
