// SPDX-License-Identifier: LGPL-3.0-or-later
// Missing-physics diagnosis: the pieces it is made of. The end-to-end proof
// on concealed data is tests/cli/diagnose.sh.
#include "breastsim_registry.hpp"
#include "candidate_scores.hpp"
#include "candidates.hpp"
#include "diagnose.hpp"
#include "errors.hpp"
#include "fit_state.hpp"
#include "fixtures.hpp"
#include "least_squares.hpp"
#include "recording.hpp"
#include "half_cap.hpp"
#include "surface_distance.hpp"
#include "surface_export.hpp"
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>

using namespace breastsim;
using namespace breastsim::calibration;
using namespace breastsim::diagnosis;

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

TEST(SurfaceDistance, ContinuousAcrossAnInnerEdgeWhateverTheTriangleOrder)
{
  // A roof: two triangles meeting at the ridge y = 0.5, z = 0.1 (normals
  // up). A point above the ridge is nearest the ridge, whose two triangles
  // give the same Euclidean distance, in either order.
  SkinSurface s;
  s.deformed = {{0, 0, 0}, {1, 0, 0}, {0, 0.5, 0.1}, {1, 0.5, 0.1}, {0, 1, 0}, {1, 1, 0}};
  const std::vector<std::array<std::int32_t, 3>> one = {{0, 1, 3}, {0, 3, 2}, {2, 3, 5}, {2, 5, 4}};
  const Point p = {0.5, 0.5, 0.3};
  s.triangles = one;
  const auto m1 = match_points(s, {p});
  s.triangles.assign(one.rbegin(), one.rend());
  const auto m2 = match_points(s, {p});
  EXPECT_TRUE(m1[0].to_point);
  EXPECT_NEAR(m1[0].distance, 0.2, 1e-14);
  EXPECT_NEAR(m2[0].distance, 0.2, 1e-14);

  // Its derivative when the ridge rises: dd = -e . dq = -dz.
  std::vector<Point> velocity(6, Point{0, 0, 0});
  velocity[2] = velocity[3] = {0, 0, 1};
  s.triangles = one;
  EXPECT_NEAR(distance_derivatives(s, {p}, m1, velocity)[0], -1.0, 1e-12);
  // Tilting the ridge's vertices: against a central difference.
  velocity[2] = {0.3, -0.2, 0.5};
  velocity[3] = {-0.1, 0.4, 0.2};
  const double h = 1e-6;
  auto moved = [&](double t)
  {
    SkinSurface m = s;
    for (std::size_t v = 0; v < m.deformed.size(); ++v)
      for (int k = 0; k < 3; ++k)
        m.deformed[v][k] += t * velocity[v][k];
    return match_points(m, {p})[0].distance;
  };
  EXPECT_NEAR(distance_derivatives(s, {p}, m1, velocity)[0], (moved(h) - moved(-h)) / (2 * h), 1e-8);
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

TEST(LevenbergMarquardt, AShortStepUnderHeavyDampingIsNotAMinimum)
{
  // r = 100 (y - 3), minimum at y = 3, from y = 0. The first seven trial
  // steps fail (chi2 huge, as when a trial's forward solves go wrong); the
  // damping they build up makes the accepted step short (3 / 17 < xtol).
  int calls = 0;
  auto f = [&calls](const std::vector<double>& y)
  {
    ++calls;
    const bool failed_trial = calls >= 3 && calls <= 9; // call 1: start, call 2: the Jacobian
    return std::vector<double>{failed_trial ? 1e6 : 100 * (y[0] - 3)};
  };
  LsqOptions o;
  o.xtol = 0.5;
  const auto r = levenberg_marquardt(f, {0.0}, {-10}, {10}, o);
  EXPECT_NEAR(r.y[0], 3.0, 1e-6) << r.stop_reason;
  EXPECT_LE(r.chi2, o.chi2_tol) << r.stop_reason;
  // Stopping on the short step alone would end at y = 3 / 17.
  calls = 0;
  o.chi2_tol = std::numeric_limits<double>::infinity();
  const auto early = levenberg_marquardt(f, {0.0}, {-10}, {10}, o);
  EXPECT_NEAR(early.y[0], 3.0 / 17, 0.01) << early.stop_reason;
}

TEST(LevenbergMarquardt, RejectedTrialsEndTheFitOnlyWhenTheyAreShort)
{
  // r = 100 (y - 3) from y = 0. Ten trial steps in a row fail: the eleventh,
  // damped to 3 / 1050 (> xtol / 10), is taken and the fit goes on to y = 3.
  int calls = 0;
  auto f = [&calls](const std::vector<double>& y)
  {
    ++calls;
    const bool failed_trial = calls >= 3 && calls <= 12;
    return std::vector<double>{failed_trial ? 1e6 : 100 * (y[0] - 3)};
  };
  const LsqOptions o;
  const auto r = levenberg_marquardt(f, {0.0}, {-10}, {10}, o);
  EXPECT_NEAR(r.y[0], 3.0, 1e-6) << r.stop_reason;
  // Where every trial fails, the trials end once they are shorter than
  // xtol / 10 (13 trials), before the 16 allowed.
  auto every_trial_fails = [](const std::vector<double>& y)
  { return std::vector<double>{100 * (y[0] - 3) + (y[0] != 0.0 ? 1e6 : 0.0)}; };
  const auto stuck = levenberg_marquardt(every_trial_fails, {0.0}, {-10}, {10}, o);
  EXPECT_EQ(stuck.y[0], 0.0);
  EXPECT_LT(stuck.evaluations, 1 + 1 + 16 + 1) << stuck.stop_reason; // start, Jacobian, trials, final J
}

TEST(LevenbergMarquardt, GaussNewtonStepSolvesTheDampedNormalEquations)
{
  // A = [[4, 1], [1, 2]], g = [1, 3]: (A + lambda diag(A)) dy = -g.
  const Matrix A = {{4, 1}, {1, 2}};
  const std::vector<double> g = {1, 3};
  for (double lambda : {0.0, 0.5})
  {
    const auto dy = gauss_newton_step(A, g, lambda);
    ASSERT_TRUE(dy && dy->size() == 2u) << lambda;
    EXPECT_NEAR((4 + 4 * lambda) * (*dy)[0] + (*dy)[1], -1, 1e-12) << lambda;
    EXPECT_NEAR((*dy)[0] + (2 + 2 * lambda) * (*dy)[1], -3, 1e-12) << lambda;
  }
  EXPECT_NEAR(gauss_newton_step(A, g).value()[0], 1.0 / 7, 1e-12); // -A^-1 g = (1/7, -11/7)
  EXPECT_FALSE(gauss_newton_step({{1, 1}, {1, 1}}, {1, 1})) << "a singular A has no step";
  const auto none = gauss_newton_step({}, {});
  EXPECT_TRUE(none && none->empty()) << "no parameters: the empty step, not a singular matrix";
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
           {"suspensory_ligament", "ligament.k"}, {"suspensory_cables", "cables.k"},
           {"gland_core", "gland.excess"}, {"skin_upper_pole", "skin_upper_pole.mu"}})
  {
    Config on = c;
    on.set("terms." + term, true);
    on.set(key, 0.0);
    for (const auto& s : candidate(term).sets) // a modulus pair: both at 0
      if (s.rule == generated::CandidateRule::keep_ratio)
        on.set(s.key, 0.0);
    const auto u1 = solve(on);
    const auto [diff, size] = fixtures::max_difference(u1, u0);
    EXPECT_LT(diff, 1e-12 * size) << term;
    // And a positive value changes the answer (the term acts).
    on = candidate(term).with(c, candidate(term).typical);
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

TEST(Candidates, TableIsWhatTheFormsDeclare)
{
  // The CANDIDATE of each term in forms/ (skin.py, skin_upper_pole.py,
  // base_springs.py, suspensory_ligament.py, suspensory_cables.py,
  // gland_core.py, gland_lobe.py), in the order of forms/registry.py.
  struct Declared
  {
    std::string name, parameter, unit, first_key;
    double typical;
    std::string family, extends;
    bool in_default_library = true;
  };
  const std::vector<Declared> declared = {
      {"skin", "skin.mu", "Pa", "skin.mu", 2e4, "skin", ""},
      {"skin_upper_pole", "skin_upper_pole.mu", "Pa", "skin_upper_pole.mu", 2e4, "skin", "skin"},
      {"base_springs", "base.compliance", "m/Pa", "base.c", 5e-6, "base_springs", ""},
      {"suspensory_ligament", "ligament.k", "Pa/m", "ligament.k", 2e3, "suspensory_ligament", ""},
      {"suspensory_cables", "cables.k", "Pa/m", "cables.k", 2e3, "suspensory_ligament", ""},
      {"gland_core", "gland.excess", "1", "gland.excess", 2.0, "gland_core", ""},
      {"gland_lobe", "gland.lobe_excess", "1", "gland.lobe_excess", 2.0, "gland_core", "", false}};
  const auto& lib = candidate_library();
  ASSERT_EQ(lib.size(), declared.size());
  for (std::size_t i = 0; i < lib.size(); ++i)
  {
    EXPECT_EQ(lib[i].name, declared[i].name);
    EXPECT_EQ(lib[i].parameter, declared[i].parameter);
    EXPECT_EQ(lib[i].unit, declared[i].unit);
    EXPECT_DOUBLE_EQ(lib[i].typical, declared[i].typical);
    EXPECT_EQ(lib[i].family, declared[i].family);
    EXPECT_EQ(lib[i].extends, declared[i].extends);
    EXPECT_EQ(lib[i].in_default_library, declared[i].in_default_library) << lib[i].name;
    ASSERT_FALSE(lib[i].sets.empty());
    EXPECT_EQ(lib[i].sets[0].key, declared[i].first_key);
    EXPECT_FALSE(lib[i].physics.empty());
  }
  EXPECT_EQ(candidate_names(),
            "skin, skin_upper_pole, base_springs, suspensory_ligament, suspensory_cables, gland_core, "
            "gland_lobe");
  // Every key a candidate sets is a parameter of its own term, and every
  // flag a case key; the candidate is a registered term.
  for (const auto& c : lib)
  {
    const auto& terms = generated::terms();
    EXPECT_TRUE(std::any_of(terms.begin(), terms.end(), [&](const auto& t) { return t.name == c.name; }))
        << c.name;
    for (const auto& s : c.sets)
    {
      const auto& ps = generated::parameters();
      EXPECT_TRUE(std::any_of(ps.begin(), ps.end(),
                              [&](const auto& p) { return p.key == s.key && p.term == c.name; }))
          << c.name << ": " << s.key;
    }
    for (const auto& [key, value] : c.flags)
      EXPECT_NO_THROW(key_info(key)) << c.name << ": " << key;
  }
  ASSERT_EQ(candidate("base_springs").flags.size(), 1u);
  EXPECT_EQ(candidate("base_springs").flags[0].first, "base.fixed");
  EXPECT_EQ(candidate("base_springs").sets[0].rule, generated::CandidateRule::inverse);
  ASSERT_EQ(candidate("skin").sets.size(), 2u);
  EXPECT_EQ(candidate("skin").sets[1].key, "skin.lambda");
  EXPECT_EQ(candidate("skin").sets[1].rule, generated::CandidateRule::keep_ratio);
}

TEST(Candidates, RulesSetTheCaseKeys)
{
  // q sets the keys by the declared rules: skin keeps lambda_s / mu_s, the
  // base springs get c = 1/q and leave the fixed base.
  Config c;
  c.set("terms.skin", false);
  c.set("skin.mu", 1000.0);
  c.set("skin.lambda", 3000.0);
  const Config skin = candidate("skin").with(c, 5000.0);
  EXPECT_TRUE(skin.flag("terms.skin"));
  EXPECT_DOUBLE_EQ(skin.number("skin.mu"), 5000.0);
  EXPECT_DOUBLE_EQ(skin.number("skin.lambda"), 3.0 * 5000.0);
  Config on;
  EXPECT_FALSE(candidate("base_springs").applicable(on)); // springs on, base free
  on.set("base.fixed", true);
  EXPECT_TRUE(candidate("base_springs").applicable(on));  // a flag differs
  const Config springs = candidate("base_springs").with(on, 2e-6);
  EXPECT_FALSE(springs.flag("base.fixed"));
  EXPECT_DOUBLE_EQ(springs.number("base.c"), 1.0 / 2e-6);
  const Config lig = candidate("suspensory_ligament").with(Config(), 1234.0);
  EXPECT_TRUE(lig.flag("terms.suspensory_ligament"));
  EXPECT_DOUBLE_EQ(lig.number("ligament.k"), 1234.0);
  EXPECT_THROW(candidate("gland_core").with(Config(), 0.0), std::invalid_argument);
}

TEST(Candidates, TheDefaultLibraryLeavesOutTheFormsNotAdmitted)
{
  // gland_lobe did not pass its pre-registered test (docs/DIAGNOSE.md): a
  // diagnosis tests it only when --candidates names it.
  EXPECT_FALSE(is_wanted(candidate("gland_lobe"), {}));
  EXPECT_TRUE(is_wanted(candidate("gland_lobe"), {"gland_lobe", "skin"}));
  EXPECT_TRUE(is_wanted(candidate("gland_core"), {}));
  EXPECT_FALSE(is_wanted(candidate("gland_core"), {"gland_lobe"}));
  EXPECT_EQ(candidates_not_default(), "gland_lobe");
}

TEST(Candidates, OneFormPerPhysics)
{
  // The ligaments as springs or as cables: a family of two forms. With one
  // form on, the other is no candidate; found, both name the ligaments.
  Config c;
  EXPECT_TRUE(candidate("suspensory_cables").applicable(c));
  EXPECT_TRUE(candidate("suspensory_ligament").applicable(c));
  const Config springs = candidate("suspensory_ligament").with(c, 1000.0);
  EXPECT_FALSE(candidate("suspensory_cables").applicable(springs));
  EXPECT_FALSE(candidate("suspensory_ligament").applicable(springs));
  EXPECT_TRUE(candidate("skin").applicable(springs) == candidate("skin").applicable(c));
  const Config cables = candidate("suspensory_cables").with(c, 1000.0);
  EXPECT_FALSE(candidate("suspensory_ligament").applicable(cables));
  EXPECT_DOUBLE_EQ(cables.number("cables.k"), 1000.0);
  EXPECT_TRUE(candidate("suspensory_cables").same_physics(candidate("suspensory_ligament")));
  EXPECT_FALSE(candidate("suspensory_cables").same_physics(candidate("skin")));
  EXPECT_EQ(physics_of({"skin", "suspensory_cables"}),
            (std::vector<std::string>{"skin", "suspensory_ligament"}));
  EXPECT_EQ(physics_of({"suspensory_cables", "suspensory_ligament"}),
            (std::vector<std::string>{"suspensory_ligament"}));
  // The gland as a full-depth core or as a buried lobe: one physics.
  const Config lobe = candidate("gland_lobe").with(c, 1.5);
  EXPECT_DOUBLE_EQ(lobe.number("gland.lobe_excess"), 1.5);
  EXPECT_FALSE(candidate("gland_core").applicable(lobe));
  EXPECT_FALSE(candidate("gland_lobe").applicable(candidate("gland_core").with(c, 1.5)));
  EXPECT_TRUE(candidate("gland_lobe").same_physics(candidate("gland_core")));
  EXPECT_EQ(physics_of({"gland_lobe", "skin"}), (std::vector<std::string>{"gland_core", "skin"}));
}

TEST(Candidates, AnExtensionAppliesOnlyOnTopOfItsBase)
{
  // skin_upper_pole refines the skin: no candidate while the skin is off,
  // one once it is on; found, it names the skin, and the skin stays in.
  Config c;
  c.set("terms.skin", false);
  const Candidate& upper = candidate("skin_upper_pole");
  EXPECT_EQ(upper.extends, "skin");
  EXPECT_TRUE(upper.same_physics(candidate("skin")));
  EXPECT_FALSE(upper.applicable(c));
  EXPECT_TRUE(candidate("skin").applicable(c));
  const Config skin = candidate("skin").with(c, 3000.0);
  EXPECT_TRUE(upper.applicable(skin));
  EXPECT_FALSE(candidate("skin").applicable(skin));
  const Config both = upper.with(skin, 2000.0);
  EXPECT_FALSE(upper.applicable(both));
  EXPECT_FALSE(candidate("skin").applicable(both));
  EXPECT_TRUE(both.flag("terms.skin"));
  EXPECT_DOUBLE_EQ(both.number("skin.mu"), 3000.0);
  EXPECT_DOUBLE_EQ(both.number("skin_upper_pole.mu"), 2000.0);
  EXPECT_EQ(physics_of({"skin", "skin_upper_pole", "suspensory_cables"}),
            (std::vector<std::string>{"skin", "suspensory_ligament"}));
  // It does not use up a round of discovery (--max-rounds counts physics).
  EXPECT_EQ(physics_found({"skin", "skin_upper_pole"}), 1);
  EXPECT_EQ(physics_found({"skin", "skin_upper_pole", "suspensory_cables"}), 2);
  EXPECT_EQ(physics_found({}), 0);
}

namespace
{
/// Largest |distance of a skin triangle's centroid from the cap's sphere - Rs|
/// of the default case's skin surface at element order `order`.
double largest_centroid_offset(int order, double h)
{
  const Config c = fixtures::coarse_case(order, h);
  auto m = fixtures::make_model(c);
  const SkinSurface s = gather_skin_surface(*m);
  const double R = c.number("geometry.R"), H = c.number("geometry.H");
  const double Rs = meshes::sphere_radius(R, H), yc = H - Rs;
  double worst = 0;
  for (const auto& t : s.triangles)
  {
    double g[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d)
        g[d] += s.reference[t[k]][d] / 3;
    worst = std::max(worst, std::abs(std::hypot(g[0], g[1] - yc, g[2]) - Rs));
  }
  return worst;
}
} // namespace

TEST(SkinSurface, P2SkinKeepsTheCurvedGeometry)
{
  // Corner facets of a 14 mm mesh lie up to h^2 / 8 Rs inside the sphere
  // (sagitta: 0.35 mm at the longest edges); a P2 facet sampled 4 x 4 is
  // within the P2 geometry's own error and the sub-facets' sagitta.
  const double p1 = largest_centroid_offset(1, 0.014), p2 = largest_centroid_offset(2, 0.014);
  EXPECT_GT(p1, 1e-4);
  EXPECT_LT(p2, 0.15 * p1) << "P1 " << p1 << " P2 " << p2;
  // The deformed surface is the quadratic map of the P2 displacement: a
  // translation of every node moves every sampled point by it.
  auto m = fixtures::make_model(fixtures::coarse_case(2, 0.016));
  auto u = m->displacement()->x()->mutable_array();
  for (std::size_t i = 0; i < u.size(); ++i)
    u[i] = (i % 3 == 2) ? -0.01 : 0.002;
  const SkinSurface s = gather_skin_surface(*m);
  ASSERT_GT(s.triangles.size(), 16u);
  EXPECT_EQ(s.triangles.size() % 16, 0u);
  for (std::size_t i = 0; i < s.reference.size(); ++i)
  {
    EXPECT_NEAR(s.deformed[i][0] - s.reference[i][0], 0.002, 1e-12);
    EXPECT_NEAR(s.deformed[i][2] - s.reference[i][2], -0.01, 1e-12);
  }
}

namespace
{
/// r(y) = A (y - y*) + b with b orthogonal to A's columns, y = ln(mu, lambda).
PointEvaluation linear_residuals(const Config& c)
{
  const double A[5][2] = {{1, 0}, {0, 1}, {1, 1}, {2, -1}, {0.5, 3}};
  const double b[5] = {1, 1, -1, 0, 0}; // A^T b = 0
  const double d[2] = {std::log(c.number("tissue.mu") / 450.0),
                       std::log(c.number("tissue.lambda") / 9000.0)};
  PointEvaluation e;
  e.distances.assign(1, {});
  for (int i = 0; i < 5; ++i)
  {
    e.r.push_back(A[i][0] * d[0] + A[i][1] * d[1] + b[i]);
    e.distances[0].push_back(1e-3 * e.r.back());
  }
  e.raw = e.distances[0];
  return e;
}
} // namespace

TEST(Diagnose, GaussNewtonRefitFromANearbyFit)
{
  // From (400, 8000) with the exact Jacobian one step lands on the optimum
  // (450, 9000), chi2 = |b|^2 = 3, in two evaluations; with a Jacobian of
  // the wrong sign the step raises chi2 and the start is kept.
  std::vector<Free> frees;
  for (const std::string key : {"tissue.mu", "tissue.lambda"})
    frees.push_back({key, "Pa", 1.0, 1e6, [key](Config& c, double v) { c.set(key, v); }, 1.0});
  Config base;
  base.set("tissue.mu", 400.0);
  base.set("tissue.lambda", 8000.0);
  FitState from;
  from.values = {400.0, 8000.0};
  from.J = {{1, 0}, {0, 1}, {1, 1}, {2, -1}, {0.5, 3}};
  int evaluations = 0;
  const Evaluate ev = [&](const Config& c)
  {
    ++evaluations;
    return linear_residuals(c);
  };
  const FitState s = gauss_newton_refit(ev, base, frees, from, "test").value();
  EXPECT_EQ(evaluations, 2);
  EXPECT_NEAR(s.values[0], 450.0, 1e-9);
  EXPECT_NEAR(s.values[1], 9000.0, 1e-8);
  EXPECT_NEAR(s.chi2, 3.0, 1e-12);
  for (auto& row : from.J)
    for (double& x : row)
      x = -x;
  const FitState kept = gauss_newton_refit(ev, base, frees, from, "test").value();
  EXPECT_NEAR(kept.values[0], 400.0, 1e-9);
  EXPECT_GT(kept.chi2, 3.0);
  // An evaluation that gives none (a posture newly left out of the finer
  // mesh) abandons the refit there, at the start or at the step.
  for (auto& row : from.J)
    for (double& x : row)
      x = -x; // the exact Jacobian again
  for (const int none_at : {1, 2})
  {
    int calls = 0;
    const Evaluate losing = [&](const Config& c) -> std::optional<PointEvaluation>
    {
      if (++calls == none_at)
        return std::nullopt;
      return linear_residuals(c);
    };
    EXPECT_FALSE(gauss_newton_refit(losing, base, frees, from, "test").has_value()) << none_at;
    EXPECT_EQ(calls, none_at);
  }
}
