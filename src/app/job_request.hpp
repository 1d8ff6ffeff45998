#pragma once
// A job request, checked at the edge before anything is queued:
//   {"kind": "simulate" | "surgery", "overrides": {key: value}}
//   {"kind": "calibrate", "overrides": {...}, "measurements": {document}
//    or "recording": {breastsim-recording/1}, "fit": "mu,c", "max_evals": 40}
//   {"kind": "sweep", "overrides": {...}, "vary": {"a": [...], "h": [...]}}
// with the library's checks and messages (case keys, the incision on the
// cap, the measurements as `calibrate` reads them, the --fit names).
#include "calibrate_request.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>

namespace breastsim::app
{
/// The request completed with its defaults; throws InputError naming the field.
nlohmann::json checked_job_request(const nlohmann::json& body);
/// The calibrate options of a checked request, its data in `data_file`.
calibration::CalibrateRequest calibrate_request(const nlohmann::json& request,
                                                const std::filesystem::path& data_file);
} // namespace breastsim::app
