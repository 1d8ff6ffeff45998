// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The report of a diagnosis: the verdict and the plain-words text (also
// printed), and diagnosis.json (breastsim-diagnosis/1, docs/DIAGNOSE.md).
#include "diagnosis.hpp"
#include <nlohmann/json.hpp>
#include <string>

namespace breastsim::diagnosis
{
/// Per posture: the numerical noise floor e_h, sigma_eff and, with a local
/// floor, the largest point floor (null otherwise) [mm].
nlohmann::json noise_floor_json(const Diagnosis& d, const Recording& rec);
nlohmann::json to_json(const Diagnosis& d, const Recording& rec);
/// The verdict in plain words (Diagnosis::verdict).
std::string verdict_text(const Diagnosis& d, const Recording& rec, double alpha);
/// The plain-words report (also printed).
std::string report_text(const Diagnosis& d, const Recording& rec);
} // namespace breastsim::diagnosis
