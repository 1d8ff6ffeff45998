// SPDX-License-Identifier: LGPL-3.0-or-later
// The checks that refuse a dirty scan (src/scan/scan_checks.hpp,
// scan_frame.hpp): a clean cap, and one with noise and small holes, are
// accepted and fitted; every defect is refused with a message naming what is
// wrong and where.
#include "errors.hpp"
#include "scan_fixtures.hpp"
#include "scan_model.hpp"
#include <gtest/gtest.h>
#include <random>

using namespace scan_fixtures;
using breastsim::InputError;

namespace
{
void expect_refused(const ScanSurface& s, const std::vector<std::string>& parts, const ScanModelOptions& o = {},
                    const ScanSurface* chest = nullptr)
{
  try
  {
    fit_scan(s, chest, o);
    ADD_FAILURE() << "accepted; expected: " << parts.front();
  }
  catch (const InputError& e)
  {
    const std::string msg = e.what();
    for (const auto& part : parts)
      EXPECT_NE(msg.find(part), std::string::npos) << "expected \"" << part << "\" in: " << msg;
  }
}

ScanSurface noisy(ScanSurface s, double sigma, unsigned seed = 3)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, sigma);
  for (Vec3& p : s.points)
    if (p[1] > 0)
      p[1] += n(rng);
  return s;
}

/// Remove the triangles with a corner within `r` of `c`.
ScanSurface with_hole(ScanSurface s, const Vec3& c, double r)
{
  std::vector<Triangle> kept;
  for (const Triangle& t : s.triangles)
    if (norm(s.points[t[0]] - c) > r && norm(s.points[t[1]] - c) > r && norm(s.points[t[2]] - c) > r)
      kept.push_back(t);
  s.triangles = kept;
  return s;
}
} // namespace

TEST(ScanChecks, AcceptsACleanCapAndANoisyCapWithSmallHoles)
{
  const ScanModel clean = fit_scan(cap_scan(), nullptr, {});
  EXPECT_LT(clean.fit_rms, 1e-5);
  EXPECT_NEAR(clean.frame.footprint_radius, 0.07, 1e-3);
  EXPECT_NEAR(norm(clean.frame.ey - Vec3{0, 1, 0}), 0, 1e-9); // the chest normal
  const ScanSurface dirty = with_hole(noisy(cap_scan(), 0.5e-3), {0.02, 0.05, 0.0}, 0.008);
  const ScanModel m = fit_scan(dirty, nullptr, {});
  EXPECT_NEAR(m.noise_rms, 0.5e-3, 0.15e-3);
  EXPECT_LT(m.fit_rms, 0.7e-3);
  const ScanMesh mesh = mesh_scan(m.fit, m.fit.radius(Vec3{0, 1, 0}) * Vec3{0, 1, 0}, {0.01, 1, false}, 1, 2, 3);
  // the full cap: pi H^2 (3 Rs - H) / 3 = 574.9 cm^3
  EXPECT_NEAR(mesh.volume, 574.9e-6, 15e-6);
  EXPECT_NEAR(mesh.nipple[1], 0.06, 1e-3);
}

TEST(ScanChecks, RefusesEmptyNonFiniteTooFewAndWrongUnits)
{
  ScanSurface s = cap_scan();
  s.points.clear();
  s.triangles.clear();
  expect_refused(s, {"empty"});
  s = cap_scan();
  s.points[17][2] = std::nan("");
  expect_refused(s, {"vertex 17 has a non-finite z coordinate"});
  expect_refused(cap_scan(0.07, 0.06, 4, 12), {"too few points: 49"});
  s = cap_scan();
  for (Vec3& p : s.points)
    p = 1e-3 * p; // a file in metres read as millimetres
  s.units = Units::mm;
  expect_refused(s, {"wrong units?", "--units mm", "is the file in metres"});
  s = cap_scan();
  for (Vec3& p : s.points)
    p = 1e3 * p;
  expect_refused(s, {"wrong units?", "--units m", "is the file in millimetres"});
}

TEST(ScanChecks, RefusesBrokenTriangles)
{
  ScanSurface s = cap_scan();
  s.triangles[40] = {s.triangles[40][0], s.triangles[40][0], s.triangles[40][2]};
  expect_refused(s, {"degenerate triangle 40"});
  s = cap_scan();
  s.triangles.push_back(s.triangles[100]);
  expect_refused(s, {"duplicated triangle", "repeats triangle 100"});
  s = cap_scan();
  s.triangles.push_back({s.triangles[100][0], s.triangles[100][1], 5}); // a third triangle on an edge
  expect_refused(s, {"non-manifold edge", "shared by 3 triangles"});
  s = cap_scan();
  std::swap(s.triangles[200][1], s.triangles[200][2]);
  expect_refused(s, {"inconsistent orientation", "triangles"});
}

TEST(ScanChecks, RefusesPiecesSelfIntersectionsAndHoles)
{
  ScanSurface s = cap_scan();
  const auto n = static_cast<std::int64_t>(s.points.size());
  s.points.insert(s.points.end(), {{0.2, 0.1, 0}, {0.21, 0.1, 0}, {0.2, 0.11, 0}});
  s.triangles.push_back({n, n + 1, n + 2});
  expect_refused(s, {"2 disconnected pieces", "triangle"});
  s = cap_scan();
  // A rim point pulled over the apex: its long triangles pass through the cap.
  s.points[1 + 19 * 72] = {0, 0.075, 0};
  expect_refused(s, {"self-intersecting triangles"});
  expect_refused(with_hole(cap_scan(), {0.0, 0.06, 0.0}, 0.02), {"hole:", "across", "--max-hole = 25.0 mm"});
}

TEST(ScanChecks, RefusesSpikesAndNoise)
{
  ScanSurface s = noisy(cap_scan(), 0.3e-3);
  s.points[1 + 12 * 72 + 30][1] += 0.015;
  expect_refused(s, {"spike: vertex 895", "off the smooth skin"});
  expect_refused(noisy(cap_scan(0.07, 0.06, 14, 40), 4e-3), {"noise:", "--max-noise = 2.00 mm"});
}

TEST(ScanChecks, RefusesAMissingOrBadFootprintAndTheWrongSide)
{
  ScanSurface cloud = cap_scan();
  cloud.triangles.clear();
  expect_refused(cloud, {"a point cloud has no open boundary", "--chest"});
  ScanSurface closed = cap_scan(); // closed by a fan over the base
  const auto c = static_cast<std::int64_t>(closed.points.size());
  closed.points.push_back({0, 0, 0});
  for (int j = 0; j < 72; ++j)
    closed.triangles.push_back({c, 1 + 23 * 72 + j, 1 + 23 * 72 + (j + 1) % 72});
  expect_refused(closed, {"footprint missing", "closed"});
  ScanSurface bent = cap_scan();
  for (int j = 0; j < 72; ++j) // a saddle: the rim up and down by 30 mm
    bent.points[1 + 23 * 72 + j][1] += 0.03 * std::cos(2 * 2 * M_PI * j / 72);
  expect_refused(bent, {"footprint not planar", "--chest"});
  ScanSurface inside_out = cap_scan();
  for (Triangle& t : inside_out.triangles)
    std::swap(t[1], t[2]);
  expect_refused(inside_out, {"wrong side", "toward the chest wall"});
}

TEST(ScanChecks, RefusesBadFrameOptions)
{
  ScanModelOptions o;
  o.frame.up = {0, 1, 0}; // along the chest normal
  expect_refused(cap_scan(), {"--up", "nearly along the chest normal"}, o);
  o = {};
  o.frame.nipple = Vec3{0, 0.2, 0};
  expect_refused(cap_scan(), {"--nipple", "from the nearest point of the scan"}, o);
}

TEST(ScanChecks, APointCloudOverAChestIsFitted)
{
  ScanSurface cloud = cap_scan();
  cloud.triangles.clear();
  ScanSurface chest;
  chest.where = "scan 'chest'";
  chest.units = Units::m;
  for (int i = -5; i <= 5; ++i)
    for (int j = -5; j <= 5; ++j)
      chest.points.push_back({0.03 * i, 0.0, 0.03 * j});
  const ScanModel m = fit_scan(cloud, &chest, {});
  EXPECT_LT(m.fit_rms, 1e-5);
  EXPECT_NEAR(m.frame.footprint_radius, 0.07, 0.01);
}

namespace
{
/// A chest wall curved about the cranial axis, y = -x^2 / (2 R) (bulging toward
/// the breast, radius R), as a triangulated 10 x 10 grid over |x|, |z| <= 0.1 m
/// with its triangles facing +y.
ScanSurface curved_chest(double R)
{
  ScanSurface chest;
  chest.where = "scan 'chest'";
  chest.units = Units::m;
  const int n = 10;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
    {
      const double x = -0.1 + 0.2 * i / n, z = -0.1 + 0.2 * j / n;
      chest.points.push_back({x, -x * x / (2 * R), z});
    }
  auto id = [&](int i, int j) -> std::int64_t { return i * (n + 1) + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
    {
      chest.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
      chest.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
    }
  return chest;
}
} // namespace

TEST(ScanChecks, MeasuresTheChestWallAgainstItsPlane)
{
  // The cap's own footprint: planar up to the fit's rounding.
  const ScanModel flat = fit_scan(cap_scan(), nullptr, {});
  EXPECT_EQ(flat.chest.source, "footprint");
  EXPECT_LT(flat.chest.plane_rms, 1e-9);
  EXPECT_FALSE(flat.chest.quadric);
  // A gently curved chest (R = 1 m): kept, its plane RMS and radius reported.
  const ScanSurface gentle = curved_chest(1.0);
  const ScanModel m = fit_scan(cap_scan(), &gentle, {});
  EXPECT_EQ(m.chest.source, "chest surface");
  EXPECT_GT(m.chest.plane_rms, 5e-4);
  EXPECT_LT(m.chest.plane_rms, 3e-3);
  ASSERT_TRUE(m.chest.quadric);
  EXPECT_LT(m.chest.quadric_rms, 1e-4); // a quadric graph, up to its flat triangles (h^2 / 8R = 0.05 mm)
  EXPECT_NEAR(m.chest.curvature_radii[0], 1.0, 0.01);
  EXPECT_TRUE(std::isinf(m.chest.curvature_radii[1]));
  // A rib cage of R = 0.25 m: the plane misplaces the base by more than 3 mm RMS.
  const ScanSurface ribs = curved_chest(0.25);
  expect_refused(cap_scan(), {"chest too curved for a planar base", "mm RMS", "--max-chest-rms = 3.00 mm"}, {},
                 &ribs);
  ScanModelOptions loose;
  loose.limits.max_chest_rms = 0.02;
  EXPECT_GT(fit_scan(cap_scan(), &ribs, loose).chest.plane_rms, 3e-3);
}
