// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A job request, checked at the edge before anything is queued:
//   {"kind": "simulate" | "surgery", "overrides": {key: value}}
//   {"kind": "calibrate", "overrides": {...}, "measurements": {document}
//    or "recording": {breastsim-recording/1}, "fit": "mu,c", "max_evals": 40}
//   {"kind": "surgery", "overrides": {incision.*, postures.*, surgery.*},
//    "scan": "<id of a finished scan job>"}: full-breast surgery on that
//    scan's neutral case (<data>/jobs/<id>/neutral/case.reference.toml)
//   {"kind": "sweep", "overrides": {...}, "vary": {"a": [...], "h": [...]}}
//   {"kind": "patient", "overrides": {...}, "patient": {breastsim-patient/1},
//    "tolerance_mm": 1}: a patient model per breast from its landmarks
//   {"kind": "plan", ... as patient, "targets": {"left": {"sn_n_mm": 210,
//    "n_imf_mm": 70, "grams": 400, "lower_pole": 0.55}, "right": {...}},
//    "symmetric": false}: goal-directed plans (docs/CLINIC.md)
// with the library's checks and messages (case keys, the incision on the
// cap, the measurements as `calibrate` reads them, the --fit names).
#include "calibrate_request.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>

namespace breastsim::app
{
/// The request completed with its defaults; throws InputError naming the field.
nlohmann::json checked_job_request(const nlohmann::json& body);
/// The keys a scanned breast's surgery takes from the request's overrides.
bool is_scan_surgery_key(const std::string& key);
/// The calibrate options of a checked request, its data in `data_file`.
calibration::CalibrateRequest calibrate_request(const nlohmann::json& request,
                                                const std::filesystem::path& data_file);
} // namespace breastsim::app
