// SPDX-License-Identifier: LGPL-3.0-or-later
// The model-form uncertainty of the found values (diagnose/model_form.hpp)
// on hand-made fits whose answers are known in closed form.
#include "model_form.hpp"
#include <cmath>
#include <gtest/gtest.h>

using namespace breastsim::diagnosis;

namespace
{
/// One posture of 8 x 4 points, x = 0..7 (spacing 1), y = 0..3 (spacing 0.1):
/// the first principal axis is x, the second y.
Recording grid_recording()
{
  Recording rec;
  rec.noise_sigma = 1e-3;
  rec.postures.resize(1);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 4; ++j)
      rec.postures[0].points.push_back({double(i), 0.1 * j, 0.0});
  return rec;
}

/// One parameter with dr/dln p = 1 at every point and residuals `r`.
FitState fit_with(const Recording& rec, std::vector<double> r)
{
  FitState s;
  s.names = {"q"};
  s.values = {2.0};
  s.uncertainty.se_log = {0.1};
  s.uncertainty.interval = {{2.0 * std::exp(-0.196), 2.0 * std::exp(0.196)}};
  s.distances = {std::vector<double>(rec.postures[0].points.size(), 0.0)};
  s.r = std::move(r);
  s.J.assign(s.r.size(), {1.0});
  return s;
}
} // namespace

// b = 2: slabs x <= 3 and x >= 4, each split at y = 0.15: four patches of 8.
TEST(ModelForm, PrincipalPatchesSplitAlongThePrincipalAxes)
{
  const Recording rec = grid_recording();
  const auto& pts = rec.postures[0].points;
  const auto patches = principal_patches(pts, 2);
  ASSERT_EQ(patches.size(), 4u);
  for (const auto& patch : patches)
  {
    ASSERT_EQ(patch.size(), 8u);
    const bool left = pts[patch[0]][0] < 3.5, low = pts[patch[0]][1] < 0.15;
    for (std::size_t i : patch)
    {
      EXPECT_EQ(pts[i][0] < 3.5, left);
      EXPECT_EQ(pts[i][1] < 0.15, low);
    }
  }
  EXPECT_EQ(principal_patches(pts, 5).size(), 1u) << "32 points are fewer than 2 x 5^2";
  EXPECT_EQ(principal_patches(pts, 0).size(), 1u);
}

// Residuals +1 on x <= 3 and -1 on x >= 4 (optimum: sum r = 0). Without a
// patch g of 8 points the step is delta_g = S_g / 24 = +-1/3, so
// se^2 = (G - 1)/G sum_g delta_g^2 = 3/4 * 4/9 = 1/3.
TEST(ModelForm, CoherentPatchesGiveAModelFormPart)
{
  const Recording rec = grid_recording();
  std::vector<double> r;
  for (const auto& p : rec.postures[0].points)
    r.push_back(p[0] < 3.5 ? 1.0 : -1.0);
  FitState s = fit_with(rec, r);
  EXPECT_NEAR(patch_jackknife_se(s, rec, 2)[0], std::sqrt(1.0 / 3.0), 1e-12);
  Diagnosis d;
  estimate_model_form(s, rec, 2, d);
  EXPECT_NEAR(d.se_posture_jackknife[0], 0.0, 1e-12) << "one posture: no posture jackknife";
  EXPECT_NEAR(d.se_model_form[0], std::sqrt(1.0 / 3.0), 1e-12) << "the larger of the two";
  widen_by_model_form(s, d.se_model_form);
  const double total = std::hypot(0.1, std::sqrt(1.0 / 3.0));
  EXPECT_NEAR(s.uncertainty.se_log[0], total, 1e-12);
  EXPECT_NEAR(s.uncertainty.interval[0][1], 2.0 * std::exp(1.96 * total), 1e-12);
}

// Residuals alternating within every patch (each patch sums to 0): the
// patches agree, no model-form part.
TEST(ModelForm, AgreeingPatchesGiveNone)
{
  const Recording rec = grid_recording();
  std::vector<double> r;
  for (const auto& p : rec.postures[0].points)
    r.push_back(std::lround(10 * p[1]) % 2 == 0 ? 1.0 : -1.0);
  EXPECT_NEAR(patch_jackknife_se(fit_with(rec, r), rec, 2)[0], 0.0, 1e-12);
  EXPECT_NEAR(patch_jackknife_se(fit_with(rec, r), rec, 0)[0], 0.0, 1e-12);
}
