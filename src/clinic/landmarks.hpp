// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A patient as the clinic measures her, standing: per breast the sternal
// notch to nipple (SN-N), nipple to inframammary fold (N-IMF), base width
// and nipple to midline, optionally projection and Regnault's ptosis grade
// (docs/CLINIC.md, "The patient file"). Read once, checked against the
// accepted ranges with the reason for each.
#include "scan_surface.hpp"
#include <filesystem>
#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace breastsim::clinic
{
/// One breast's landmarks, standing [m].
struct SideLandmarks
{
  double sn_n = 0, n_imf = 0, base_width = 0, nipple_midline = 0;
  std::optional<double> projection;
  std::optional<int> ptosis_grade; ///< 0 (none) to 3
};

/// The patient's body, optional: height and weight give the body surface
/// area (Mosteller), against which resections are weighed (grams per m^2).
struct Body
{
  std::optional<double> height;    ///< [m]
  std::optional<double> weight_kg; ///< [kg]
  std::string bra_size;            ///< as the patient gives it, e.g. "36DD" (recorded, not modelled)
  /// Mosteller: BSA = sqrt(height [cm] x weight [kg] / 3600) m^2; needs both.
  std::optional<double> surface_area() const;
};

/// The standing scan of one breast (docs/CLINIC.md, "A scanned breast"):
/// N-IMF, base width, projection and ptosis grade are measured on it, and
/// SN-N and the nipple's distance from the midline too when a notch is given.
struct SideScan
{
  std::filesystem::path file;
  scan::Units units = scan::Units::mm;
  std::optional<std::array<double, 3>> nipple, notch; ///< landmarks in the scanner frame [m]
  std::array<double, 3> up{0, 0, 1}, lateral{1, 0, 0}; ///< cranial, and toward this breast's axilla (scanner frame)
};

struct Patient
{
  std::string id;                             ///< the patient's ID (as the clinic writes it)
  std::map<std::string, SideLandmarks> sides; ///< "left" and/or "right" (a scanned side: the entered part)
  std::map<std::string, SideScan> scans;      ///< the sides given as a scan
  std::optional<Body> body;
};

/// An accepted range of a landmark [m] and why it is bounded so.
struct LandmarkRange
{
  std::string key;
  double lo, hi;
  std::string why;
};
const std::vector<LandmarkRange>& landmark_ranges();
/// The range of landmark `key` that `value` [m] lies outside, or nullptr.
const LandmarkRange* violated_range(const std::string& key, double value);

/// The patient document `breastsim-patient/1` (docs/CLINIC.md). Throws
/// InputError naming the key, the value (in the file's unit) and the
/// accepted range with its reason.
Patient patient_from_json(const nlohmann::json& j, const std::string& source);
/// As patient_from_json; a scan's relative file name is taken from the patient file's folder.
Patient read_patient(const std::filesystem::path& file);
nlohmann::json to_json(const SideLandmarks& s); ///< in mm
nlohmann::json to_json(const Body& b);          ///< height_m, weight_kg, bra_size, bsa_m2 (those given)
} // namespace breastsim::clinic
