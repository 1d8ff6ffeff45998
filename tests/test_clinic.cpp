// SPDX-License-Identifier: LGPL-3.0-or-later
// The consulting room's measures and patient model (src/clinic): tape
// measures on an exact spherical cap against their closed forms, the
// patient file's checks, and patient models that reproduce their landmarks.
#include "errors.hpp"
#include "input_error_message.hpp"
#include "landmarks.hpp"
#include "patient_fit.hpp"
#include "skin_measures.hpp"
#include "surgical_terms.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <tuple>

using namespace breastsim;
using namespace breastsim::clinic;

namespace
{
constexpr double pi = 3.14159265358979323846;

/// The half cap x >= 0 of base radius R and height H as a fine triangle
/// surface: rings at angle t from the apex (sphere radius rho, centre
/// (0, H - rho, 0)), azimuth psi in [0, pi] from the upper meridian.
SkinSurface half_cap(double R, double H, int rings = 160, int sectors = 160)
{
  const double rho = (R * R + H * H) / (2 * H), alpha = std::acos(1 - H / rho);
  SkinSurface s;
  s.reference.push_back({0, H, 0});
  for (int i = 1; i <= rings; ++i)
    for (int j = 0; j <= sectors; ++j)
    {
      const double t = alpha * i / rings, psi = pi * j / sectors;
      double y = H - rho + rho * std::cos(t);
      if (i == rings)
        y = 0; // the rim exactly on the chest
      s.reference.push_back({rho * std::sin(t) * std::sin(psi), y, rho * std::sin(t) * std::cos(psi)});
    }
  auto v = [&](int i, int j) { return i == 0 ? 0 : 1 + (i - 1) * (sectors + 1) + j; };
  for (int j = 0; j < sectors; ++j)
    s.triangles.push_back({v(0, 0), v(1, j), v(1, j + 1)});
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < sectors; ++j)
    {
      s.triangles.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      s.triangles.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  s.deformed = s.reference;
  s.half_model = true;
  return s;
}
} // namespace

TEST(SkinMeasures, MeridianOfACapIsItsArc)
{
  const double R = 0.07, H = 0.06, rho = (R * R + H * H) / (2 * H);
  const SkinSurface s = half_cap(R, H);
  Point fold{};
  const double arc = nipple_to_fold(s, {0, H, 0}, &fold);
  EXPECT_NEAR(arc, rho * std::acos(1 - H / rho), 1e-5);
  EXPECT_NEAR(fold[2], -R, 1e-12);
  EXPECT_NEAR(base_width(s), 2 * R, 1e-6);
  const Meridian m = skin_meridian(s, {0, H, 0});
  EXPECT_NEAR(m.points.front()[2], R, 1e-12); // the upper end first
}

TEST(SkinMeasures, TautTapeFromAboveIsTangentPlusArc)
{
  // Notch straight above the nipple at z = zn: the tape is the tangent from
  // the notch to the sphere, then the arc to the apex.
  const double R = 0.07, H = 0.06, zn = 0.15, rho = (R * R + H * H) / (2 * H);
  const SkinSurface s = half_cap(R, H, 240, 240);
  const double dy = rho - H, d = std::hypot(dy, zn);
  const double angle = std::atan2(zn, dy) - std::acos(rho / d);
  ASSERT_GT(angle, 0);
  const double expected = std::sqrt(d * d - rho * rho) + rho * angle;
  EXPECT_NEAR(taut_tape(s, {0, 0, zn}, {0, H, 0}, 2e-4), expected, 2e-4);
}

TEST(SkinMeasures, TapeFromTheMidlineCrossesTheMirroredHalf)
{
  // The notch medial of the breast (x < 0): the tape runs over the mirror
  // image of the half model; on a flat chest (far from the breast) it is
  // the straight distance.
  const SkinSurface s = half_cap(0.05, 0.04);
  EXPECT_NEAR(skin_height(s, -0.02, 0.0), skin_height(s, 0.02, 0.0), 1e-12);
  EXPECT_GT(skin_height(s, -0.02, 0.0), 0.0);
  EXPECT_EQ(skin_height(s, 0.3, 0.3), 0.0);
  const double tape = taut_tape(s, {-0.1, 0, 0.2}, {0, 0.04, 0});
  EXPECT_GT(tape, std::hypot(0.1, 0.2, 0.04) - 1e-9); // never shorter than the chord
  EXPECT_LT(tape, std::hypot(0.1, 0.2) + 0.04);
}

TEST(SkinMeasures, DeformedPositionFollowsTheSkin)
{
  SkinSurface s = half_cap(0.07, 0.06, 40, 40);
  for (auto& p : s.deformed)
    p = {p[0] + 0.001, p[1] - 0.002, p[2] - 0.01};
  const Point q = deformed_position(s, {0, 0.06, 0});
  EXPECT_NEAR(q[0], 0.001, 1e-12);
  EXPECT_NEAR(q[1], 0.058, 1e-12);
  EXPECT_NEAR(q[2], -0.01, 1e-12);
}

TEST(SkinMeasures, PtosisGrades)
{
  EXPECT_EQ(ptosis_grade(-0.02), 0);
  EXPECT_EQ(ptosis_grade(-0.005), 1);
  EXPECT_EQ(ptosis_grade(0.01), 1);
  EXPECT_EQ(ptosis_grade(0.02), 2);
  EXPECT_EQ(ptosis_grade(0.05), 3);
}

namespace
{
nlohmann::json patient_doc()
{
  return nlohmann::json::parse(R"({"format": "breastsim-patient/1", "id": "T-1", "units": "cm",
    "left": {"sn_n": 24, "n_imf": 9, "base_width": 13, "nipple_midline": 10, "ptosis_grade": 1},
    "right": {"sn_n": 240, "n_imf": 9, "base_width": 13, "nipple_midline": 10}})");
}

std::string refusal(const nlohmann::json& j)
{
  return fixtures::message_of([&] { patient_from_json(j, "p.json"); });
}
} // namespace

TEST(Landmarks, ReadsLengthsInTheFilesUnit)
{
  auto j = patient_doc();
  j["right"]["sn_n"] = 25.5;
  const Patient p = patient_from_json(j, "p.json");
  EXPECT_EQ(p.id, "T-1");
  EXPECT_DOUBLE_EQ(p.sides.at("right").sn_n, 0.255);
  EXPECT_EQ(*p.sides.at("left").ptosis_grade, 1);
  EXPECT_FALSE(p.sides.at("right").projection.has_value());
}

TEST(Landmarks, BodySurfaceAreaIsMostellers)
{
  // 165 cm, 68 kg: sqrt(165 x 68 / 3600) = 1.76540 m^2; the height in the file's unit (mm here).
  auto j = patient_doc();
  j["right"]["sn_n"] = 25.5;
  j["units"] = "mm";
  for (const char* side : {"left", "right"})
    for (auto& [k, v] : j[side].items())
      if (k != "ptosis_grade")
        v = 10 * v.get<double>();
  j["body"] = {{"height", 1650}, {"weight_kg", 68}, {"bra_size", "36DD"}};
  const Patient p = patient_from_json(j, "p.json");
  ASSERT_TRUE(p.body.has_value());
  EXPECT_DOUBLE_EQ(*p.body->height, 1.65);
  EXPECT_NEAR(*p.body->surface_area(), std::sqrt(165.0 * 68 / 3600), 1e-12);
  EXPECT_EQ(to_json(*p.body).at("bra_size"), "36DD");
  j["body"] = {{"weight_kg", 68}};
  EXPECT_FALSE(patient_from_json(j, "p.json").body->surface_area().has_value()); // needs both
  j["body"] = {{"height", 2650}};
  EXPECT_NE(refusal(j).find("'body.height' = 2650 mm is out of range: [1200, 2200] mm"), std::string::npos)
      << refusal(j);
  j["body"] = {{"weight", 68}};
  EXPECT_NE(refusal(j).find("did you mean 'weight_kg'"), std::string::npos) << refusal(j);
}

TEST(Landmarks, RefusesWithKeyValueAndRange)
{
  // A nipple 240 cm from the notch: the key, the value, the range and why.
  const std::string e = refusal(patient_doc());
  EXPECT_NE(e.find("'right.sn_n' = 240 cm is out of range: [15, 45] cm"), std::string::npos) << e;
  auto j = patient_doc();
  j["right"]["sn_n"] = 24;
  j["left"]["nipple_midlin"] = 10;
  EXPECT_NE(refusal(j).find("did you mean 'nipple_midline'"), std::string::npos) << refusal(j);
  j = patient_doc();
  j.erase("units");
  EXPECT_NE(refusal(j).find("'units' must be one of mm, cm, m"), std::string::npos);
  j = patient_doc();
  j["right"] = {{"sn_n", 24}, {"n_imf", 9}, {"base_width", 24}, {"nipple_midline", 10}};
  EXPECT_NE(refusal(j).find("would cross the midline"), std::string::npos) << refusal(j);
  j = patient_doc();
  j["left"]["ptosis_grade"] = 4;
  EXPECT_NE(refusal(j).find("'left.ptosis_grade' = 4 is out of range: an integer 0-3"), std::string::npos);
  j = patient_doc();
  j.erase("left");
  j.erase("right");
  EXPECT_NE(refusal(j).find("give the landmarks"), std::string::npos);
}

namespace
{
Config coarse_case()
{
  Config c;
  c.set("geometry.mesh_size", 0.012);
  c.set("postures.names", std::vector<std::string>{"standing"});
  return c;
}
} // namespace

TEST(PatientFit, ReproducesTheLandmarksOfBothBreasts)
{
  // An asymmetric patient: the right breast wider, the left ptotic (grade 2,
  // which scales the moduli down to about 5 %). The landmarks are judged on
  // a mesh generated at the fitted shape (the surgery's): the right within
  // 1 mm on a 12 mm mesh; the soft left breast's landmarks differ by up to
  // 3 mm between two 12 mm meshes of nearby shapes, so it is fitted on the
  // default 8 mm mesh, within 1.5 mm.
  SideLandmarks left{0.26, 0.10, 0.14, 0.105, std::nullopt, 2};
  SideLandmarks right{0.245, 0.09, 0.135, 0.10, 0.065, std::nullopt};
  Config fine = coarse_case();
  fine.set("geometry.mesh_size", 0.008);
  for (const auto& [side, t, c, tol] :
       {std::tuple{"left", left, fine, 1.5e-3}, std::tuple{"right", right, coarse_case(), 1e-3}})
  {
    const SideModel m = fit_side(c, side, t, tol, MPI_COMM_WORLD);
    const auto& a = m.achieved.landmarks;
    EXPECT_NEAR(a.sn_n, t.sn_n, tol) << side;
    EXPECT_NEAR(a.n_imf, t.n_imf, tol) << side;
    EXPECT_NEAR(a.base_width, t.base_width, tol) << side;
    EXPECT_NEAR(a.nipple_midline, t.nipple_midline, 1e-12) << side;
    EXPECT_LE(m.largest_error, tol) << side;
    if (t.ptosis_grade)
    {
      EXPECT_EQ(m.achieved.ptosis_grade, *t.ptosis_grade);
      EXPECT_LT(m.stiffness_factor, 1.0); // a ptotic breast is laxer than the default
    }
    else
      EXPECT_EQ(m.stiffness_factor, 1.0);
    // The notch lies on the chest, medial of the nipple and above it.
    EXPECT_NEAR(m.notch[0], -t.nipple_midline, 1e-12);
    EXPECT_GT(m.notch[2], m.achieved.nipple[2]);
  }
}

TEST(PatientFit, RefusesAnUnreachableBreastNamingTheLandmark)
{
  // An 8 cm base cannot hang a 25 cm lower pole: H is at most 1.5 R.
  SideLandmarks t{0.30, 0.25, 0.08, 0.10, std::nullopt, std::nullopt};
  try
  {
    fit_side(coarse_case(), "left", t, 1e-3, MPI_COMM_WORLD);
    FAIL() << "no refusal";
  }
  catch (const InputError& e)
  {
    const std::string m = e.what();
    EXPECT_NE(m.find("N-IMF of 25.0 cm"), std::string::npos) << m;
    EXPECT_NE(m.find("the closest it came is"), std::string::npos) << m;
  }
}

TEST(SurgicalTerms, ResectedVolumeEqualsTheCadVolume)
{
  // The column quadrature against OCC's volume of the resected part, for
  // the paper's incision and a wider, higher one.
  const HalfCapSpec cap{0.07, 0.06, 0.012};
  for (const IncisionSpec in : {IncisionSpec{}, IncisionSpec{40, 0.03, 0.02, 0.03}})
  {
    double half = 0;
    meshes::mesh_resected_part(cap, in, {1, 2, 3, 4, 5}, &half);
    EXPECT_NEAR(resected_volume(cap, meshes::incision_geometry(cap, in)) / (2 * half), 1.0, 2e-3) << in.a_deg;
  }
}

TEST(SurgicalTerms, AngleForGramsInvertsTheWeight)
{
  const HalfCapSpec cap{0.07, 0.06, 0.012};
  IncisionSpec in;
  in.a_deg = angle_for_grams(cap, in, 150.0, 970.0);
  EXPECT_NEAR(1e3 * 970 * resected_volume(cap, meshes::incision_geometry(cap, in), 300), 150.0, 0.05);
  try
  {
    angle_for_grams(cap, IncisionSpec{}, 5000.0, 970.0);
    FAIL() << "no refusal";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("a resection of 5000 g is out of reach"), std::string::npos) << e.what();
  }
}
