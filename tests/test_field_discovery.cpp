// SPDX-License-Identifier: LGPL-3.0-or-later
// Field discovery's parts (diagnose/field_*.hpp): the basis lattice, the
// ridge penalty chosen on held-out postures, the field in words, and the
// written UFL term.
#include "field_basis.hpp"
#include "field_ridge.hpp"
#include "field_summary.hpp"
#include "field_term_writer.hpp"
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <random>
#include <sstream>
#include <unistd.h>

using namespace breastsim::diagnosis;

TEST(FieldBasis, LatticeFillsTheHalfCapWithinTheCompiledSize)
{
  const double R = 0.07, H = 0.06;
  const FieldBasis b = lattice_basis(R, H);
  EXPECT_GE(b.centres.size(), 16u);
  EXPECT_LE(b.centres.size(), max_field_basis);
  for (const auto& c : b.centres)
    EXPECT_TRUE(in_half_cap(c, R, H));
  EXPECT_GT(b.width, 0.01);
  // s(X) at a centre with one unit amplitude is 1; far away it vanishes.
  std::vector<double> a(b.centres.size(), 0.0);
  a[3] = 1;
  EXPECT_NEAR(field_value(b, a, b.centres[3]), 1.0, 1e-14);
  EXPECT_LT(std::abs(field_value(b, a, {1, 1, 1})), 1e-12);
}

TEST(FieldBasis, CaseCarriesTheFieldPaddedToTheCompiledSize)
{
  const FieldBasis b = lattice_basis(0.07, 0.06);
  const auto c = with_field(breastsim::Config(), b, {0.5, -0.25});
  EXPECT_TRUE(c.flag("terms.tissue_field"));
  const auto& a = c.numbers("tissue_field.amplitudes");
  ASSERT_EQ(a.size(), max_field_basis);
  EXPECT_EQ(a[0], 0.5);
  EXPECT_EQ(a[1], -0.25);
  EXPECT_EQ(a[2], 0.0);
  EXPECT_EQ(c.numbers("tissue_field.centres")[3], b.centres[1][0]);
  EXPECT_EQ(c.number("tissue_field.width"), b.width);
}

namespace
{
/// A linear problem of 4 "postures" x 300 rows: r = -(A a_true + B d_true) + noise.
struct Problem
{
  Matrix A, B;
  std::vector<double> r;
  std::vector<std::vector<std::size_t>> rows;
};

Problem problem(const std::vector<double>& a_true, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, 1);
  Problem p;
  p.rows.resize(4);
  for (std::size_t i = 0; i < 1200; ++i)
  {
    p.rows[i / 300].push_back(i);
    std::vector<double> ai, bi = {n(rng)};
    double model = 0.3 * bi[0];
    for (std::size_t k = 0; k < a_true.size(); ++k)
    {
      // smooth columns: a bump along the row index of each posture
      const double t = static_cast<double>(i % 300) / 300 - static_cast<double>(k) / a_true.size();
      ai.push_back(8 * std::exp(-t * t / 0.01) * (1 + 0.2 * static_cast<double>(i / 300)));
      model += ai.back() * a_true[k];
    }
    p.A.push_back(ai);
    p.B.push_back(bi);
    p.r.push_back(-model + n(rng));
  }
  return p;
}
} // namespace

TEST(FieldRidge, RecoversAFieldThePosturesShareAndGainsOnHeldOutPostures)
{
  const std::vector<double> a_true = {0.0, 0.5, 1.0, 0.5, 0.0, 0.0};
  const Problem p = problem(a_true, 3);
  const RidgeChoice c = choose_ridge(p.A, p.B, p.r, p.rows);
  ASSERT_EQ(c.a.size(), a_true.size());
  for (std::size_t k = 0; k < a_true.size(); ++k)
    EXPECT_NEAR(c.a[k], a_true[k], 0.1) << k;
  EXPECT_NEAR(c.d[0], 0.3, 0.1);
  EXPECT_GT(c.total_gain, 100.0);
  for (double g : c.held_out_gain)
    EXPECT_GT(g, 0.0);
  EXPECT_GT(c.dof, 1.0);
  EXPECT_LE(c.dof, static_cast<double>(a_true.size()) + 1e-9);
  EXPECT_EQ(c.path.size(), 15u);
}

TEST(FieldRidge, ZeroMeanFieldLeavesTheUniformPartToTheModel)
{
  const std::vector<double> a_true = {0.0, 0.5, 1.0, 0.5, 0.0, 0.0};
  const Problem p = problem(a_true, 3);
  const std::vector<double> m = {0.1, 0.2, 0.2, 0.2, 0.2, 0.1};
  const RidgeChoice c = choose_ridge(p.A, p.B, p.r, p.rows, m);
  double mean = 0;
  for (std::size_t k = 0; k < m.size(); ++k)
    mean += m[k] * c.a[k];
  EXPECT_NEAR(mean, 0.0, 1e-4);
  EXPECT_GT(c.total_gain, 100.0); // what is left of the field still predicts
}

TEST(FieldRidge, NoiseAloneGainsNothingOnHeldOutPostures)
{
  const Problem p = problem(std::vector<double>(6, 0.0), 5);
  const RidgeChoice c = choose_ridge(p.A, p.B, p.r, p.rows);
  // The best held-out gain of pure noise is at most a few chi2 units (the
  // heaviest penalty shrinks the field to almost nothing).
  EXPECT_LT(c.total_gain, 5.0);
  EXPECT_LT(c.dof, 2.0);
}

TEST(FieldSummary, OneStiffRegionInTheLowerPoleIsNamedWithItsFactor)
{
  const double R = 0.07, H = 0.06;
  FieldBasis b;
  b.centres = {{0.02, 0.015, -0.04}};
  b.width = 0.01;
  const FieldSummary f = summarise_field(b, {std::log(3.0)}, {{0.01}}, R, H);
  EXPECT_NEAR(f.factor, 3.0, 0.05); // the 2 mm sampling lattice misses the centre by <= 1.7 mm
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(f.centroid[k], b.centres[0][k], 0.002) << k;
  // |s| >= s_peak / 2 within r = w sqrt(2 ln 2) = 11.8 mm: about 24 mm across
  EXPECT_NEAR(f.extent_mm[2], 24.0, 3.0);
  EXPECT_LT(f.factor_lo, 3.0);
  EXPECT_GT(f.factor_hi, 3.0);
  // SE of s at the centre = sqrt(0.01) = 0.1: interval exp(ln 3 -+ 0.196)
  EXPECT_NEAR(f.factor_hi / f.factor_lo, std::exp(2 * 1.96 * 0.1), 0.02);
  EXPECT_NE(f.where.find("lower pole"), std::string::npos) << f.where;
  EXPECT_NE(f.where.find("deep"), std::string::npos) << f.where;
  EXPECT_NE(f.resembles.find("a stiffer region of tissue"), std::string::npos) << f.resembles;

  const FieldSummary soft = summarise_field(b, {std::log(0.5)}, {}, R, H);
  EXPECT_NEAR(soft.factor, 0.5, 0.01);
  EXPECT_NE(soft.resembles.find("softer"), std::string::npos) << soft.resembles;
}

TEST(FieldTermWriter, WritesEveryValueExactlyAsATermOfForms)
{
  FieldDiscovery f;
  f.basis.centres = {{0.01, 0.02, -0.03}, {0.015, 0.025, 0.0}};
  f.basis.width = 0.0134;
  f.amplitudes = {0.123456789012345, -0.5};
  f.summary.words = "the tissue is 1.1 x as stiff in the lower pole";
  f.summary.where = "in the lower pole";
  const std::string s = field_term_source(f, "found_stiffness", "rec.json");
  for (const char* must : {"NAME = \"found_stiffness\"", "q_found_stiffness = Constant(domain)",
                           "AMPLITUDES = [0.123456789012345, -0.5]", "(0.01, 0.02, -0.03)",
                           "WIDTH = 0.0134", "CANDIDATE = candidate(\"found_stiffness.strength\"",
                           "ENERGY = q_found_stiffness * (exp(s_field) - 1)", "the tissue is 1.1 x"})
    EXPECT_NE(s.find(must), std::string::npos) << must << "\n" << s;
}

TEST(FieldTermWriter, WrittenTermCompilesWithFfcxBesideTheForms)
{
  // The file plus one line in forms/registry.py: ffcx compiles its kernels
  // (P2), as the build does (forms/compile_module.py).
  namespace fs = std::filesystem;
  FieldDiscovery f;
  f.basis = lattice_basis(0.07, 0.06);
  f.amplitudes.assign(f.basis.centres.size(), 0.0);
  f.amplitudes[2] = 0.7;
  f.summary.words = "a test field";
  const fs::path dir = fs::temp_directory_path() / fs::path("breastsim_field_term_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "out");
  for (const auto& e : fs::directory_iterator(fs::path(BREASTSIM_SOURCE_DIR) / "forms"))
    if (e.path().extension() == ".py")
      fs::copy_file(e.path(), dir / e.path().filename());
  std::ofstream(dir / "found_stiffness.py") << field_term_source(f, "found_stiffness", "test");
  std::stringstream registry;
  registry << std::ifstream(dir / "registry.py").rdbuf();
  std::string text = registry.str();
  const std::size_t end = text.rfind(']');
  ASSERT_NE(end, std::string::npos);
  text.insert(end, "    \"found_stiffness\",\n");
  std::ofstream(dir / "registry.py") << text;
  std::ofstream(dir / "entry_found_stiffness_p2.py")
      << "import os\nos.environ['BREASTSIM_DEGREE'] = '2'\nos.environ['BREASTSIM_TERM'] = "
         "'found_stiffness'\nfrom term_forms import *  # noqa\n";
  const std::string cmd = "cd '" + dir.string() + "' && PYTHONPATH=. /usr/bin/python3 compile_module.py "
                          "entry_found_stiffness_p2.py out out/dep.d > out/log.txt 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << [&] { std::stringstream l; l << std::ifstream(dir / "out/log.txt").rdbuf(); return l.str(); }();
  EXPECT_TRUE(fs::exists(dir / "out/entry_found_stiffness_p2.c"));
  fs::remove_all(dir);
}
