// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A scanned breast in the consultation (docs/APP.md, "Consultation"): the
// browser uploads the standing scan (POST /api/scans?use=consultation, kept
// and checked, not modelled) and names it in the patient document by that
// upload's job id, {"scan": {"upload": "<id>", ...}}. The server alone
// turns the id into its stored file and unit: no path from a request
// reaches the disk.
#include <filesystem>
#include <nlohmann/json.hpp>

namespace breastsim::app
{
/// The patient document with each side's scan {"upload": id, and optionally
/// nipple, notch, up, lateral} given the file and unit of that upload, read
/// from `jobs`/<id>/request.json. With `jobs` empty (checking a request
/// before it is queued) the id is checked and a placeholder file named.
/// InputError for another key (file, units), an id that is not a job id, or
/// an upload that is not a consultation scan.
nlohmann::json resolve_patient_scans(const nlohmann::json& patient, const std::filesystem::path& jobs);
} // namespace breastsim::app
