// SPDX-License-Identifier: LGPL-3.0-or-later
// Law discovery's parts (diagnose/feature_selection.hpp, law_discovery.hpp):
// features chosen on held-out postures, the law in words, and the written
// UFL term.
#include "feature_selection.hpp"
#include "law_discovery.hpp"
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <random>
#include <sstream>
#include <unistd.h>

using namespace breastsim::diagnosis;

namespace
{
/// 4 postures x 300 rows, 3 feature columns and one free parameter:
/// r = -(A b_true + B d_true) + noise. The features differ by posture (a
/// posture-dependent strain), as the tissue law's do.
struct Problem
{
  Matrix A, B;
  std::vector<double> r;
  std::vector<std::vector<std::size_t>> rows;
};

Problem problem(const std::vector<double>& b_true, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, 1);
  Problem p;
  p.rows.resize(4);
  for (std::size_t i = 0; i < 1200; ++i)
  {
    const std::size_t posture = i / 300;
    p.rows[posture].push_back(i);
    const double t = static_cast<double>(i % 300) / 300, s = 1 + 0.5 * static_cast<double>(posture);
    const std::vector<double> a = {20 * s * t * t, 20 * s * s * t * t * t, 20 * std::sin(3 * t + posture)};
    const std::vector<double> b = {5 * (0.5 + n(rng) * 0.1)};
    double model = 0.2 * b[0];
    for (std::size_t k = 0; k < a.size(); ++k)
      model += a[k] * b_true[k];
    p.A.push_back(a);
    p.B.push_back(b);
    p.r.push_back(-model + n(rng));
  }
  return p;
}
} // namespace

TEST(FeatureSelection, ChoosesTheFeaturesTheTruthHas)
{
  const Problem p = problem({0.8, 0.0, 0.0}, 7);
  const FeatureChoice c = choose_features(p.A, p.B, p.r, p.rows);
  ASSERT_EQ(c.features, std::vector<std::size_t>({0}));
  EXPECT_NEAR(c.b[0], 0.8, 0.05);
  EXPECT_GT(c.total_gain, 100.0);
  for (double g : c.held_out_gain)
    EXPECT_GT(g, 0.0);
  EXPECT_EQ(c.tried.size(), 6u); // 3 singles, 3 pairs
}

TEST(FeatureSelection, NoiseAloneChoosesNothingAndNegativeLawsAreSkipped)
{
  const Problem p = problem({0.0, 0.0, 0.0}, 11);
  const FeatureChoice c = choose_features(p.A, p.B, p.r, p.rows);
  EXPECT_LT(c.total_gain, 10.0);
  const Problem softer = problem({-0.8, 0.0, 0.0}, 12); // b < 0: outside the family
  const FeatureChoice s = choose_features(softer.A, softer.B, softer.r, softer.rows, 1);
  EXPECT_TRUE(s.features.empty() || s.features[0] != 0);
  EXPECT_TRUE(std::isnan(s.tried[0].second));
}

TEST(LawDiscovery, EnergyRatioInUniaxialStretchIsTheClosedForm)
{
  // lambda = 1.2: I1b - 3 = 1.44 + 2/1.2 - 3 = 0.10667, I2b - 3 = 2.4 + 1/1.44 - 3 = 0.09444.
  const double i1 = 1.44 + 2 / 1.2 - 3, i2 = 2.4 + 1 / 1.44 - 3, mu = 500;
  EXPECT_NEAR(law_energy_ratio({0, 0, 0}, mu, 1.2), 1.0, 1e-15);
  EXPECT_NEAR(law_energy_ratio({300, 50, 20}, mu, 1.2),
              1 + (300 * i1 * i1 + 50 * i1 * i1 * i1 + 20 * i2) / (mu / 2 * i1), 1e-12);
  const std::string w = law_words({300, 0, 0}, mu);
  EXPECT_NE(w.find("stiffens with strain"), std::string::npos) << w;
  const std::string mr = law_words({0, 0, 100}, mu);
  EXPECT_NE(mr.find("29 % of the small-strain shear"), std::string::npos) << mr; // 200 / 700
  EXPECT_EQ(law_words({0, 0, 0}, mu), "no feature beyond eq. (5)");
}

TEST(LawDiscovery, WrittenTermCompilesWithFfcxBesideTheForms)
{
  namespace fs = std::filesystem;
  LawDiscovery l;
  l.coefficients = {123.456789, 0.0, 7.5};
  l.words = "a test law";
  const std::string text = law_term_source(l, "found_law", "test");
  EXPECT_NE(text.find("COEFFICIENTS = [123.456789, 0, 7.5]"), std::string::npos) << text;
  const fs::path dir = fs::temp_directory_path() / fs::path("breastsim_law_term_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "out");
  for (const auto& e : fs::directory_iterator(fs::path(BREASTSIM_SOURCE_DIR) / "forms"))
    if (e.path().extension() == ".py")
      fs::copy_file(e.path(), dir / e.path().filename());
  std::ofstream(dir / "found_law.py") << text;
  std::stringstream registry;
  registry << std::ifstream(dir / "registry.py").rdbuf();
  std::string reg = registry.str();
  reg.insert(reg.rfind(']'), "    \"found_law\",\n");
  std::ofstream(dir / "registry.py") << reg;
  std::ofstream(dir / "entry_found_law_p2.py")
      << "import os\nos.environ['BREASTSIM_DEGREE'] = '2'\nos.environ['BREASTSIM_TERM'] = "
         "'found_law'\nfrom term_forms import *  # noqa\n";
  const std::string cmd = "cd '" + dir.string() + "' && PYTHONPATH=. /usr/bin/python3 compile_module.py "
                          "entry_found_law_p2.py out out/dep.d > out/log.txt 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_TRUE(fs::exists(dir / "out/entry_found_law_p2.c"));
  fs::remove_all(dir);
}
