// Missing-physics diagnosis (issue 7): the pieces it is made of. The
// end-to-end proof on concealed data is tests/cli/diagnose.sh.
#include "candidates.hpp"
#include "diagnose.hpp"
#include "errors.hpp"
#include "fixtures.hpp"
#include "least_squares.hpp"
#include "recording.hpp"
#include "surface_distance.hpp"
#include <cmath>
#include <gtest/gtest.h>

using namespace breastsim;
using namespace breastsim::calibration;

TEST(SurfaceDistance, ClosestPointOnTriangleRegions)
{
  const Point a = {0, 0, 0}, b = {1, 0, 0}, c = {0, 1, 0};
  auto near = [](const Point& p, const Point& q)
  { return std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]) < 1e-14; };
  EXPECT_TRUE(near(closest_point_on_triangle({0.2, 0.3, 5}, a, b, c), {0.2, 0.3, 0}));   // interior
  EXPECT_TRUE(near(closest_point_on_triangle({0.5, -2, 1}, a, b, c), {0.5, 0, 0}));      // edge AB
  EXPECT_TRUE(near(closest_point_on_triangle({-1, 0.4, 0}, a, b, c), {0, 0.4, 0}));      // edge AC
  EXPECT_TRUE(near(closest_point_on_triangle({1, 1, 0}, a, b, c), {0.5, 0.5, 0}));       // edge BC
  EXPECT_TRUE(near(closest_point_on_triangle({-1, -1, 3}, a, b, c), a));                 // vertex A
  EXPECT_TRUE(near(closest_point_on_triangle({3, -0.5, 0}, a, b, c), b));                // vertex B
  EXPECT_TRUE(near(closest_point_on_triangle({-0.5, 4, -1}, a, b, c), c));               // vertex C
}

TEST(SurfaceDistance, SignedNormalDistanceToASurface)
{
  // The plane z = 0 as a triangulated square, normals +z (counter-clockwise
  // seen from z > 0): points above are outside (+), below inside (-).
  SkinSurface s;
  for (double x : {0.0, 1.0})
    for (double y : {0.0, 1.0})
      s.deformed.push_back({x, y, 0});
  s.triangles = {{0, 2, 1}, {1, 2, 3}}; // vertices (0,0), (0,1), (1,0), (1,1)
  const auto m = match_points(s, {{0.3, 0.6, 0.002}, {0.7, 0.2, -0.004}, {1.5, 0.5, 0.001}});
  EXPECT_NEAR(m[0].distance, 0.002, 1e-15);
  EXPECT_NEAR(m[1].distance, -0.004, 1e-15);
  // Beyond the rim the tangential offset is ignored: only the normal part counts.
  EXPECT_NEAR(m[2].distance, 0.001, 1e-15);
}

TEST(Diagnose, BoundaryCorrectedCriticalValue)
{
  // 0.5 P(chi2_1 > x) = level: P(chi2_1 > 10.828) = 0.001, P(chi2_1 > 2.706) = 0.1.
  EXPECT_NEAR(boundary_lr_critical(0.0005), 10.828, 1e-3);
  EXPECT_NEAR(boundary_lr_critical(0.05), 2.706, 1e-3);
}

TEST(Diagnose, LevenbergMarquardtRecoversAnExponentialModel)
{
  // r_i(y) = a exp(-b t_i) - data_i in y = (ln a, ln b), bounded.
  std::vector<double> t, data;
  for (int i = 0; i < 30; ++i)
  {
    t.push_back(0.1 * i);
    data.push_back(2.5 * std::exp(-1.3 * t.back()));
  }
  auto f = [&](const std::vector<double>& y)
  {
    std::vector<double> r;
    for (std::size_t i = 0; i < t.size(); ++i)
      r.push_back(std::exp(y[0]) * std::exp(-std::exp(y[1]) * t[i]) - data[i]);
    return r;
  };
  LsqOptions o;
  o.fd_step = 1e-7;
  o.xtol = 1e-10;
  o.ftol_rel = 0;
  o.max_iterations = 100;
  const auto r = levenberg_marquardt(f, {0.0, 0.0}, {-3, -3}, {3, 3}, o);
  EXPECT_NEAR(std::exp(r.y[0]), 2.5, 1e-5);
  EXPECT_NEAR(std::exp(r.y[1]), 1.3, 1e-5);
  // A bound that excludes the optimum is respected.
  const auto rb = levenberg_marquardt(f, {0.0, 0.0}, {-3, -3}, {3, std::log(1.0)}, o);
  EXPECT_LE(std::exp(rb.y[1]), 1.0 + 1e-12);
}

namespace
{
nlohmann::json good_recording()
{
  nlohmann::json pts = nlohmann::json::array();
  for (int i = 0; i < 12; ++i)
    pts.push_back({0.001 * i, 0.05, -0.01});
  return {{"format", "breastsim-recording/1"},
          {"noise_sigma", 0.0005},
          {"known", {{"R", 0.07}, {"H", 0.06}}},
          {"postures", {{{"name", "standing"}, {"theta_deg", 0}, {"points", pts},
                         {"landmarks", {{"nipple", {0, 0.059, -0.02}}}}}}}};
}

std::string error_of(const nlohmann::json& j)
{
  try
  {
    parse_recording(j, "test.json");
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST(Recording, ParsesTheDocumentedFormat)
{
  const auto r = parse_recording(good_recording(), "test.json");
  ASSERT_EQ(r.postures.size(), 1u);
  EXPECT_EQ(r.postures[0].points.size(), 12u);
  ASSERT_TRUE(r.postures[0].nipple.has_value());
  EXPECT_DOUBLE_EQ(r.known.at("R"), 0.07);
  // Round trip.
  const auto r2 = parse_recording(to_json(r), "again");
  EXPECT_EQ(r2.postures[0].points, r.postures[0].points);
}

TEST(Recording, BadInputsNameTheKey)
{
  auto j = good_recording();
  j["format"] = "other/2";
  EXPECT_NE(error_of(j).find("key 'format'"), std::string::npos);
  j = good_recording();
  j["noise_sigma"] = -1;
  EXPECT_NE(error_of(j).find("key 'noise_sigma' = -1"), std::string::npos);
  j = good_recording();
  j["postures"][0]["points"][3][1] = 55.0; // millimetres
  EXPECT_NE(error_of(j).find("postures[0].points[3][1]"), std::string::npos);
  EXPECT_NE(error_of(j).find("not mm"), std::string::npos);
  j = good_recording();
  j["postures"][0]["points"][2][0] = -0.01; // the other half
  EXPECT_NE(error_of(j).find("x >= 0"), std::string::npos);
  j = good_recording();
  j["postures"][0]["points"][1] = {0.0, 0.01};
  EXPECT_NE(error_of(j).find("[x, y, z]"), std::string::npos);
  j = good_recording();
  j["postures"][0].erase("theta_deg");
  EXPECT_NE(error_of(j).find("postures[0].theta_deg' is missing"), std::string::npos);
  j = good_recording();
  j["postures"].push_back(j["postures"][0]);
  EXPECT_NE(error_of(j).find("appears twice"), std::string::npos);
  j = good_recording();
  j["colour"] = "red";
  EXPECT_NE(error_of(j).find("key 'colour' is not allowed"), std::string::npos);
  j = good_recording();
  j["postures"][0]["points"].erase(0);
  j["postures"][0]["points"].erase(0);
  j["postures"][0]["points"].erase(0);
  EXPECT_NE(error_of(j).find("at least 10 points"), std::string::npos);
}

TEST(Candidates, EachIsNestedAtItsNullValue)
{
  // Switching a candidate term on at q = 0 reproduces the model without it
  // (base_springs: the fixed base is its c -> infinity limit, tested in
  // Physics.StiffSpringsReproduceTheFixedBase).
  Config c = fixtures::coarse_case(1, 0.016);
  auto solve = [](const Config& cfg)
  {
    auto m = fixtures::make_model(cfg);
    fixtures::solve_gravity(*m, {0, 0, -9.81});
    auto x = m->displacement()->x()->array();
    return std::vector<double>(x.begin(), x.end());
  };
  const auto u0 = solve(c);
  for (const auto& [term, key] : std::vector<std::pair<std::string, std::string>>{
           {"suspensory_ligament", "ligament.k"}, {"gland_core", "gland.excess"}})
  {
    Config on = c;
    on.set("terms." + term, true);
    on.set(key, 0.0);
    const auto u1 = solve(on);
    const auto [diff, size] = fixtures::max_difference(u1, u0);
    EXPECT_LT(diff, 1e-12 * size) << term;
    // And a positive value changes the answer (the term acts).
    on.set(key, candidate(term).typical);
    const auto u2 = solve(on);
    double change = 0;
    for (std::size_t i = 0; i < u0.size(); ++i)
      change = std::max(change, std::abs(u2[i] - u0[i]));
    EXPECT_GT(change, 1e-2 * size) << term;
  }
  Config skin_off = c;
  skin_off.set("terms.skin", false);
  EXPECT_TRUE(candidate("skin").applicable(skin_off));
  EXPECT_FALSE(candidate("skin").applicable(c));
  const Config with = candidate("skin").with(skin_off, 5000.0);
  EXPECT_TRUE(with.flag("terms.skin"));
  EXPECT_DOUBLE_EQ(with.number("skin.mu"), 5000.0);
  Config fixed = c;
  fixed.set("base.fixed", true);
  fixed.set("terms.base_springs", false);
  const Config springs = candidate("base_springs").with(fixed, 1e-6);
  EXPECT_FALSE(springs.flag("base.fixed"));
  EXPECT_DOUBLE_EQ(springs.number("base.c"), 1e6);
  EXPECT_THROW(candidate("dark_matter"), InputError);
}
