// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Calibration input: what is measured on the patient (docs/CALIBRATION.md).
// A measurement file (JSON, SI units) is read and checked here, once; every
// error names the key and the value.
#include "posture.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace breastsim::calibration
{
/// Which model observable a measurement is compared with.
enum class Quantity
{
  projection,     ///< max y over the skin [m]
  z_min,          ///< lowest skin point [m]
  z_max,          ///< highest skin point [m]
  height,         ///< z_max - z_min (vertical extent of the breast) [m]
  nipple_x,       ///< nipple position [m]
  nipple_y,
  nipple_z,
  base_perimeter  ///< perimeter of the base of the full breast [m]
};

std::string quantity_name(Quantity q);

struct Measurement
{
  std::size_t posture = 0; ///< index into Measurements::postures
  Quantity quantity = Quantity::projection;
  double value = 0;        ///< measured value [m]
  double sigma = 0;        ///< standard deviation of the measurement error [m]
  std::string label;       ///< e.g. "standing.projection"
};

struct Measurements
{
  std::vector<Posture> postures; ///< postures the model must be solved in
  std::vector<Measurement> items;
};

/// Parse and check a measurement document (`source` names it in errors).
Measurements parse_measurements(const nlohmann::json& doc, const std::string& source);
/// Read a measurement file; InputError for unreadable, invalid or inconsistent files.
Measurements read_measurements(const std::filesystem::path& file);
} // namespace breastsim::calibration
