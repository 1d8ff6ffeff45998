// SPDX-License-Identifier: LGPL-3.0-or-later
// The numerical noise floor spread over the points (each point's own, over
// its neighbourhood) and the regions it whitens.
#include "fixtures.hpp"
#include "diagnosis_report.hpp"
#include "mesh_error.hpp"
#include "point_neighbours.hpp"
#include "residual_regions.hpp"
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

using namespace breastsim;
using namespace breastsim::calibration;
using namespace breastsim::diagnosis;

namespace
{
/// A 20 x 20 grid of points 5 mm apart in the plane y = 0.
std::vector<Point> grid_points()
{
  std::vector<Point> pts;
  for (int a = 0; a < 20; ++a)
    for (int b = 0; b < 20; ++b)
      pts.push_back({0.005 * a, 0.0, 0.005 * b});
  return pts;
}

/// 0.6 mm on the 3 x 3 points of the grid's corner (a, b < 3), 0.01 mm elsewhere.
std::vector<double> corner_change()
{
  std::vector<double> c;
  for (int a = 0; a < 20; ++a)
    for (int b = 0; b < 20; ++b)
      c.push_back(a < 3 && b < 3 ? 6e-4 : 1e-5);
  return c;
}
} // namespace

TEST(NoiseFloor, NearestNeighboursAreTheClosestPoints)
{
  const auto knn = nearest_neighbours(grid_points(), 4);
  std::vector<std::size_t> n = knn[21]; // (1, 1): its four neighbours at 5 mm
  std::sort(n.begin(), n.end());
  EXPECT_EQ(n, (std::vector<std::size_t>{1, 20, 22, 41}));
}

TEST(NoiseFloor, LocalFloorKeepsAConcentratedMeshError)
{
  const auto pts = grid_points();
  const auto change = corner_change();
  const auto e = local_floor(pts, change, 12);
  // (1, 1): itself, its 8 patch neighbours and 4 points outside the patch.
  EXPECT_NEAR(e[21], std::sqrt((9 * 36e-8 + 4 * 1e-10) / 13), 1e-12);
  EXPECT_NEAR(e[399], 1e-5, 1e-15); // far from the patch: its own change
  double ss = 0;
  for (double c : change)
    ss += c * c;
  const double posture_rms = std::sqrt(ss / change.size()); // the posture's e_h
  EXPECT_LT(posture_rms, 0.2 * e[21]);
}

TEST(NoiseFloor, UniformChangeGivesTheSameFloorEverywhere)
{
  const auto pts = grid_points();
  const auto e = local_floor(pts, std::vector<double>(pts.size(), -3e-5), 12);
  for (double v : e)
    EXPECT_NEAR(v, 3e-5, 1e-15);
}

TEST(NoiseFloor, RegionsAreFoundInTheWhitenedResiduals)
{
  Recording rec;
  rec.noise_sigma = 5e-4;
  rec.postures.push_back({"standing", 0, grid_points(), std::nullopt});
  FitState f;
  f.config = fixtures::coarse_case();
  f.distances = {std::vector<double>(400, 0.0)};
  f.nipple_error = {{NAN, NAN, NAN}};
  for (int a = 0; a < 20; ++a)
    for (int b = 0; b < 20; ++b)
      f.distances[0][20 * a + b] = (a < 3 && b < 3) ? 1e-3 : 0.0; // 2 sigma on the corner
  const auto whiten = [&](const std::vector<double>& sigma)
  {
    f.r.clear();
    for (std::size_t i = 0; i < 400; ++i)
      f.r.push_back(f.distances[0][i] / sigma[i]);
  };
  whiten(std::vector<double>(400, rec.noise_sigma));
  const auto regions = locate_regions(rec, f, 12, 4.0);
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_NEAR(regions[0].mean_residual * regions[0].points, 9e-3, 1e-12);
  // The same distances where the local floor is 1 mm: no region.
  std::vector<double> sigma(400, rec.noise_sigma);
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      sigma[20 * a + b] = std::hypot(rec.noise_sigma, 1e-3);
  whiten(sigma);
  EXPECT_TRUE(locate_regions(rec, f, 12, 4.0).empty());
}

TEST(NoiseFloor, JsonGivesTheLargestPointFloor)
{
  Recording rec;
  rec.noise_sigma = 5e-4;
  rec.postures.push_back({});
  rec.postures[0].name = "standing";
  Diagnosis d;
  d.noise_sigma = rec.noise_sigma;
  d.mesh_error = {5e-5};
  d.sigma_eff = {std::hypot(5e-4, 5e-5)};
  auto j = noise_floor_json(d, rec); // no local floor measured: null
  EXPECT_TRUE(j[0]["local_mesh_error_max_mm"].is_null());
  EXPECT_NEAR(j[0]["mesh_error_mm"].get<double>(), 0.05, 1e-12);
  d.local_floor_max = {7e-4};
  j = noise_floor_json(d, rec);
  EXPECT_NEAR(j[0]["local_mesh_error_max_mm"].get<double>(), 0.7, 1e-12);
}
