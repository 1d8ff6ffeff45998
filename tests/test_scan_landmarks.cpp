// SPDX-License-Identifier: LGPL-3.0-or-later
// A breast entered as its standing scan (src/clinic/scan_landmarks.hpp):
// the tape measures on a hemisphere's scan against their closed forms, the
// model-to-scan distance and volume of a skin against itself, and the
// patient file's refusals for scanned sides.
#include "errors.hpp"
#include "input_error_message.hpp"
#include "landmarks.hpp"
#include "scan_fixtures.hpp"
#include "scan_landmarks.hpp"
#include "scan_writers.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using namespace breastsim;
using namespace breastsim::clinic;

namespace
{
constexpr double R = 0.07; // the hemisphere's radius [m]

/// A hemisphere's skin written as an STL in mm; the scan as a patient file gives it.
SideScan hemisphere_scan(const scan_fixtures::ScratchDir& dir)
{
  SideScan s;
  s.file = dir.path / "hemisphere.stl";
  scan::write_scan(scan_fixtures::cap_scan(R, R), s.file, scan::ScanFormat::stl_binary, scan::Units::mm);
  return s;
}

std::string refusal(const nlohmann::json& j)
{
  return fixtures::message_of([&] { patient_from_json(j, "p.json"); });
}
} // namespace

TEST(ScanLandmarks, HemisphereMeasuresAreItsClosedForms)
{
  const scan_fixtures::ScratchDir dir;
  const ScannedSkin s = read_scanned_skin(hemisphere_scan(dir));
  const ScanMeasures m = measure_scan(s, std::nullopt);
  // N-IMF a quarter of a great circle, width the diameter, projection the radius.
  EXPECT_NEAR(m.landmarks.n_imf, std::numbers::pi * R / 2, 5e-4);
  EXPECT_NEAR(m.landmarks.base_width, 2 * R, 5e-4);
  EXPECT_NEAR(*m.landmarks.projection, R, 3e-4);
  EXPECT_EQ(*m.landmarks.ptosis_grade, 0); // the nipple 7 cm above the fold
  EXPECT_NEAR(m.fold[2], -R, 5e-4);
  EXPECT_NEAR(s.volume, 2 * std::numbers::pi * R * R * R / 3, 0.01 * 2 * std::numbers::pi * R * R * R / 3);
  EXPECT_NEAR(volume_under(s.skin), s.volume, 0.01 * s.volume);
}

TEST(ScanLandmarks, NotchGivesTheTautTapeAndTheMidline)
{
  const scan_fixtures::ScratchDir dir;
  const ScannedSkin s = read_scanned_skin(hemisphere_scan(dir));
  // The notch 10 cm medial and 15 cm above the base's centre, on the chest.
  const ScanMeasures m = measure_scan(s, Point{-0.10, 0.0, 0.15});
  // Tangent from the notch to the sphere's profile, then its arc to the apex:
  // sqrt(L^2 - R^2) + R (pi / 2 - acos(R / L)).
  const double L = std::hypot(0.10, 0.15);
  EXPECT_NEAR(m.landmarks.sn_n, std::sqrt(L * L - R * R) + R * (std::numbers::pi / 2 - std::acos(R / L)), 5e-4);
  EXPECT_NEAR(m.landmarks.nipple_midline, 0.10, 1e-6);
  try
  {
    measure_scan(s, Point{0.10, 0.0, 0.15});
    FAIL() << "a notch lateral of the nipple was accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("lateral of the nipple"), std::string::npos) << e.what();
  }
}

TEST(ScanLandmarks, SkinAgainstItselfIsZeroAndRaysLandOnIt)
{
  const scan_fixtures::ScratchDir dir;
  const ScannedSkin s = read_scanned_skin(hemisphere_scan(dir));
  const ScanMeasures m = measure_scan(s, std::nullopt);
  const ScanComparison c = compare_with_scan(s, m.fold, s.skin, m.fold);
  EXPECT_LT(c.max, 1e-12);
  EXPECT_NEAR(c.volume_model, c.volume_scan, 0.01 * c.volume_scan);
  // A point twice as far out lands on the sphere along its ray.
  const Point p = onto_scan(s, {0.0, 0.0, 0.0}, {0.06, 0.08, 0.0});
  EXPECT_NEAR(std::hypot(p[0], p[1], p[2]), R, 3e-4);
  EXPECT_NEAR(p[0] / p[1], 0.75, 1e-9);
}

TEST(ScanLandmarks, PatientFileRefusesWhatTheScanMeasures)
{
  auto doc = [](const nlohmann::json& left)
  {
    return nlohmann::json{{"format", "breastsim-patient/1"}, {"units", "cm"}, {"left", left}};
  };
  const nlohmann::json scan = {{"file", "l.stl"}, {"units", "mm"}};
  const Patient p = patient_from_json(doc({{"scan", scan}, {"sn_n", 24}, {"nipple_midline", 10}}), "p.json");
  ASSERT_EQ(p.scans.count("left"), 1u);
  EXPECT_EQ(p.scans.at("left").file, "l.stl");
  EXPECT_NEAR(p.sides.at("left").sn_n, 0.24, 1e-12);
  EXPECT_NE(refusal(doc({{"scan", scan}, {"sn_n", 24}, {"nipple_midline", 10}, {"n_imf", 9}}))
                .find("'left.n_imf' is measured on the scan"), std::string::npos);
  EXPECT_NE(refusal(doc({{"scan", scan}, {"sn_n", 24}})).find("'left.nipple_midline' is missing"), std::string::npos);
  nlohmann::json with_notch = scan;
  with_notch["notch"] = {-100, 0, 150};
  EXPECT_NE(refusal(doc({{"scan", with_notch}, {"sn_n", 24}})).find("measured on the scan from its notch"),
            std::string::npos);
  nlohmann::json typo = scan;
  typo["nippel"] = {0, 70, 0};
  EXPECT_NE(refusal(doc({{"scan", typo}, {"sn_n", 24}, {"nipple_midline", 10}})).find("did you mean 'nipple'"),
            std::string::npos);
  nlohmann::json units = scan;
  units["units"] = "cm";
  EXPECT_NE(refusal(doc({{"scan", units}, {"sn_n", 24}, {"nipple_midline", 10}})).find("'left.scan.units' must be mm or m"),
            std::string::npos);
}
