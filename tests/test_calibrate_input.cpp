// SPDX-License-Identifier: LGPL-3.0-or-later
// Calibration input checking (measurement files, --fit), the uncertainty
// algebra and the checkpoint: no forward solves.
#include "checkpoint.hpp"
#include "errors.hpp"
#include "fit_parameters.hpp"
#include "measurements.hpp"
#include "uncertainty.hpp"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <tuple>

using namespace breastsim;
using namespace breastsim::calibration;
using nlohmann::json;

namespace
{
json valid_doc()
{
  return json::parse(R"({
    "units": "SI", "sigma": 0.0005,
    "base_perimeter": 0.434, "breast_height": {"value": 0.141, "sigma": 0.002},
    "postures": [
      {"name": "standing", "projection": 0.0595, "z_min": -0.077, "nipple": [0, 0.0595, -0.022]},
      {"theta_deg": 40, "projection": {"value": 0.055, "sigma": 0.001}, "sigma": 0.0008, "z_max": 0.07},
      {"name": "supine", "base_perimeter": 0.445}
    ]})");
}

/// The InputError message of parsing `doc`, or "" if it parses.
std::string error_of(const json& doc)
{
  try
  {
    parse_measurements(doc, "test.json");
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}

std::filesystem::path temp_file(const std::string& name, const std::string& text)
{
  const auto p = std::filesystem::temp_directory_path() / name;
  std::ofstream(p) << text;
  return p;
}
} // namespace

TEST(CalibrateInput, ValidFileGivesEveryMeasurementWithItsSigma)
{
  const Measurements m = parse_measurements(valid_doc(), "test.json");
  ASSERT_EQ(m.postures.size(), 3u);
  EXPECT_EQ(m.postures[1].theta_deg, 40.0);
  ASSERT_EQ(m.items.size(), 2u + 3u + 2u + 1u + 2u);
  auto find = [&](const std::string& label) -> const Measurement&
  {
    for (const auto& x : m.items)
      if (x.label == label)
        return x;
    throw std::runtime_error("no measurement " + label);
  };
  EXPECT_DOUBLE_EQ(find("standing.nipple_z").value, -0.022);
  EXPECT_DOUBLE_EQ(find("standing.nipple_z").sigma, 0.0005);     // file default
  EXPECT_DOUBLE_EQ(find("theta_40.projection").sigma, 0.001);    // per value
  EXPECT_DOUBLE_EQ(find("theta_40.z_max").sigma, 0.0008);        // per posture
  EXPECT_DOUBLE_EQ(find("breast_height").sigma, 0.002);
  EXPECT_EQ(find("base_perimeter").posture, 0u);                 // measured standing
  EXPECT_EQ(find("base_perimeter").quantity, Quantity::base_perimeter);
  EXPECT_EQ(find("breast_height").quantity, Quantity::height);
}

TEST(CalibrateInput, MissingOrEmptyPostureListIsRefused)
{
  json d = valid_doc();
  d.erase("postures");
  EXPECT_NE(error_of(d).find("'postures' is missing"), std::string::npos) << error_of(d);
  d["postures"] = json::array();
  EXPECT_NE(error_of(d).find("'postures' must be a non-empty list"), std::string::npos);
  d = valid_doc();
  d["postures"][2].erase("base_perimeter");
  EXPECT_NE(error_of(d).find("has no measured value"), std::string::npos) << error_of(d);
  d = valid_doc();
  d["postures"][0].erase("name");
  EXPECT_NE(error_of(d).find("exactly one of 'name'"), std::string::npos) << error_of(d);
  d = valid_doc();
  d["postures"][0]["name"] = "handstand";
  EXPECT_NE(error_of(d).find("unknown posture 'handstand'"), std::string::npos) << error_of(d);
}

TEST(CalibrateInput, NegativePerimeterIsRefusedNamingTheKey)
{
  json d = valid_doc();
  d["base_perimeter"] = -0.43;
  const std::string e = error_of(d);
  EXPECT_NE(e.find("'base_perimeter' = -0.43"), std::string::npos) << e;
  EXPECT_NE(e.find("must be > 0"), std::string::npos) << e;
  d = valid_doc();
  d["postures"][2]["base_perimeter"] = 0.0;
  EXPECT_NE(error_of(d).find("'supine.base_perimeter' = 0"), std::string::npos) << error_of(d);
}

TEST(CalibrateInput, NaNIsRefusedInMemoryAndInFiles)
{
  json d = valid_doc();
  d["postures"][0]["z_min"] = std::nan("");
  EXPECT_NE(error_of(d).find("'standing.z_min' = nan is not a finite number"), std::string::npos)
      << error_of(d);
  d = valid_doc();
  d["postures"][0]["nipple"][1] = "0.05";
  EXPECT_NE(error_of(d).find("'standing.nipple_y' = \"0.05\" is not a number"), std::string::npos)
      << error_of(d);
  const auto f = temp_file("breastsim_nan_measurements.json",
                           R"({"units": "SI", "postures": [{"name": "standing", "projection": NaN}]})");
  try
  {
    read_measurements(f);
    FAIL() << "NaN accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("not valid JSON"), std::string::npos) << e.what();
  }
  std::filesystem::remove(f);
}

TEST(CalibrateInput, UnitsKeyMustBePresentAndSI)
{
  json d = valid_doc();
  d["units"] = "mm";
  EXPECT_NE(error_of(d).find("'units' = \"mm\" is not allowed"), std::string::npos) << error_of(d);
  d.erase("units");
  EXPECT_NE(error_of(d).find("'units' is missing"), std::string::npos) << error_of(d);
  // Millimetre numbers in an "SI" file are caught too.
  d = valid_doc();
  d["postures"][0]["projection"] = 59.5;
  EXPECT_NE(error_of(d).find("not mm"), std::string::npos) << error_of(d);
}

TEST(CalibrateInput, UnknownKeysAndBadSigmaAreRefused)
{
  json d = valid_doc();
  d["postures"][0]["projektion"] = 0.05;
  EXPECT_NE(error_of(d).find("'postures[0].projektion' is not allowed"), std::string::npos)
      << error_of(d);
  d = valid_doc();
  d["sigma"] = 0;
  EXPECT_NE(error_of(d).find("'sigma' = 0 is out of range"), std::string::npos) << error_of(d);
  d = valid_doc();
  d["postures"].push_back({{"theta_deg", 0}, {"projection", 0.05}});
  EXPECT_NE(error_of(d).find("repeats the posture"), std::string::npos) << error_of(d);
}

TEST(CalibrateFit, DensityWithStiffnessIsRefusedAsUnidentifiable)
{
  const Config c;
  try
  {
    parse_fit("rho,mu", c);
    FAIL() << "rho with mu accepted";
  }
  catch (const InputError& e)
  {
    const std::string m = e.what();
    EXPECT_NE(m.find("'rho' and 'mu' cannot be fitted together"), std::string::npos) << m;
    EXPECT_NE(m.find("ratio"), std::string::npos) << m;
  }
  EXPECT_THROW(parse_fit("c,rho", c), InputError);
  EXPECT_NO_THROW(parse_fit("rho", c));
  EXPECT_NO_THROW(parse_fit("rho,R,H", c));
  EXPECT_THROW(parse_fit("mu,nu", c), InputError);
  EXPECT_THROW(parse_fit("mu,mu", c), InputError);
  EXPECT_THROW(parse_fit("", c), InputError);
}

TEST(CalibrateFit, AliasesAreWhatTheFormsDeclare)
{
  // FIT of forms/tissue.py, gravity.py, skin.py, base_springs.py and
  // GEOMETRY_FIT of forms/common.py, in the order of forms/registry.py.
  using generated::FitRole;
  const std::vector<std::tuple<std::string, std::string, FitRole>> declared = {
      {"mu", "tissue.mu", FitRole::stiffness},     {"lambda", "tissue.lambda", FitRole::stiffness},
      {"rho", "tissue.rho", FitRole::density},     {"mu_s", "skin.mu", FitRole::stiffness},
      {"lambda_s", "skin.lambda", FitRole::stiffness}, {"c", "base.c", FitRole::stiffness},
      {"R", "geometry.R", FitRole::shape},         {"H", "geometry.H", FitRole::shape}};
  const auto& aliases = generated::fit_aliases();
  ASSERT_EQ(aliases.size(), declared.size());
  for (std::size_t i = 0; i < aliases.size(); ++i)
  {
    EXPECT_EQ(aliases[i].alias, std::get<0>(declared[i]));
    EXPECT_EQ(aliases[i].key, std::get<1>(declared[i]));
    EXPECT_EQ(aliases[i].role, std::get<2>(declared[i]));
    EXPECT_NO_THROW(key_info(aliases[i].key)) << aliases[i].key; // a case key
  }
  // An alias resolves, through --fit too; an unknown one lists them all.
  EXPECT_EQ(fit_alias("lambda_s").key, "skin.lambda");
  const Config c;
  const auto fit = parse_fit("lambda_s,H", c);
  EXPECT_EQ(fit[0].key, "skin.lambda");
  EXPECT_EQ(fit[0].unit, "Pa");
  EXPECT_EQ(fit[1].role, FitRole::shape);
  try
  {
    fit_alias("nu");
    FAIL() << "unknown alias accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("allowed: " + fit_alias_names()), std::string::npos) << e.what();
  }
}

TEST(CalibrateFit, BoundsAndLogCoordinates)
{
  Config c;
  const auto fit = parse_fit("mu, c,R", c);
  ASSERT_EQ(fit.size(), 3u);
  EXPECT_EQ(fit[1].key, "base.c");
  EXPECT_DOUBLE_EQ(fit[0].lower, 400.0 / 30);
  EXPECT_DOUBLE_EQ(fit[0].upper, 400.0 * 30);
  EXPECT_DOUBLE_EQ(fit[2].upper, 0.07 * 1.25);
  const auto y = to_log(fit, c);
  EXPECT_NEAR(y[0], std::log(400.0), 1e-14);
  const Config d = with_parameters(c, fit, {std::log(800.0), y[1], std::log(0.08)});
  EXPECT_NEAR(d.number("tissue.mu"), 800.0, 1e-9);
  EXPECT_NEAR(d.number("geometry.R"), 0.08, 1e-15);
  EXPECT_TRUE(changes_geometry(fit));
}

TEST(CalibrateUncertainty, GaussNewtonCovarianceOfALinearModel)
{
  // r = J y - b: Cov = (J^T J)^-1. J^T J = [[2, 1], [1, 2]], inverse [[2, -1], [-1, 2]] / 3.
  const Matrix J = {{1, 0}, {0, 1}, {1, 1}};
  const auto u = gauss_newton_uncertainty(J, {0.0, std::log(2.0)}, {"a", "b"});
  ASSERT_FALSE(u.singular);
  EXPECT_NEAR(u.se_log[0], std::sqrt(2.0 / 3), 1e-12);
  EXPECT_NEAR(u.correlation[0][1], -0.5, 1e-12);
  EXPECT_NEAR(u.interval[1][0], 2 * std::exp(-1.96 * std::sqrt(2.0 / 3)), 1e-12);
  // A variance factor (reduced chi2) of 4 doubles the SE, keeps the correlation.
  const auto w = gauss_newton_uncertainty(J, {0.0, 0.0}, {"a", "b"}, 4.0);
  EXPECT_NEAR(w.se_log[0], 2 * std::sqrt(2.0 / 3), 1e-12);
  EXPECT_NEAR(w.correlation[0][1], -0.5, 1e-12);
}

TEST(CalibrateUncertainty, NearlyDependentParametersAreFlagged)
{
  const Matrix J = {{1e3, 1e3 * (1 + 1e-3)}, {2e3, 2e3 * (1 - 1e-3)}, {1e3, 1e3}};
  const auto u = gauss_newton_uncertainty(J, {0.0, 0.0}, {"mu", "c"});
  ASSERT_FALSE(u.singular);
  EXPECT_NE(u.flags[0].find("correlated with c"), std::string::npos) << u.flags[0];
  EXPECT_NE(u.flags[1].find("correlated with mu"), std::string::npos) << u.flags[1];
  const auto s = gauss_newton_uncertainty({{1, 2}, {2, 4}}, {0.0, 0.0}, {"mu", "c"});
  EXPECT_TRUE(s.singular);
  EXPECT_NE(s.flags[0].find("not identifiable"), std::string::npos);
  const auto weak = gauss_newton_uncertainty({{10, 0}, {0, 0.1}}, {0.0, 0.0}, {"mu", "c"});
  EXPECT_EQ(weak.flags[0], "");
  EXPECT_NE(weak.flags[1].find("poorly determined"), std::string::npos) << weak.flags[1];
}

TEST(CalibrateCheckpoint, RoundTripAndMismatch)
{
  const Config c;
  const auto fit = parse_fit("mu,c", c);
  const auto f = std::filesystem::temp_directory_path() / "breastsim_test_checkpoint.json";
  write_checkpoint(f, {{"mu", "c"}, {std::log(300.0), std::log(1.5e5)}, 12.5, 17});
  const Checkpoint cp = read_checkpoint(f, fit);
  EXPECT_EQ(cp.evaluations, 17);
  EXPECT_DOUBLE_EQ(cp.best_chi2, 12.5);
  EXPECT_NEAR(std::exp(cp.best_y[0]), 300.0, 1e-9);
  EXPECT_THROW(read_checkpoint(f, parse_fit("mu,lambda", c)), InputError);
  std::filesystem::remove(f);
  EXPECT_THROW(read_checkpoint(f, fit), InputError);
}

TEST(CalibrateOutput, CalibratedCaseRoundTripsThroughToml)
{
  // calibrated.toml is Config::to_toml of the case: every key, each TOML
  // table once (base.fixed and base.c live in the same [base] table).
  Config c;
  c.set("base.c", 123456.789);
  c.set("tissue.mu", 321.5);
  c.set("base.fixed", true);
  const auto f = temp_file("breastsim_test_calibrated.toml", c.to_toml());
  const Config back = Config::from_file(f);
  EXPECT_EQ(back.number("base.c"), 123456.789);
  EXPECT_EQ(back.number("tissue.mu"), 321.5);
  EXPECT_TRUE(back.flag("base.fixed"));
  EXPECT_EQ(back.to_json(), c.to_json());
  std::filesystem::remove(f);
}
