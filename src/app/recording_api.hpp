// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A 3D surface recording (breastsim-recording/1, as `breastsim record`
// writes and `calibrate` reads it) sent by the page: checked as `calibrate`
// reads it (parse_recording: its messages), with a bound on the points the
// server fits (the body size limit bounds the bytes).
#include <cstddef>
#include <nlohmann/json.hpp>

namespace breastsim::app
{
/// Most skin points of a recording in all postures.
inline constexpr std::size_t max_recording_points = 20000;

/// {"ok": true, "noise_sigma_m", "known": {R, H, rho}, "points", "postures":
/// [{"name", "theta_deg", "points", "nipple": bool}]}; InputError with the
/// library's message (key, value, allowed range) otherwise.
nlohmann::json check_recording(const nlohmann::json& doc);
/// The page's check of a file: check_recording, or {"ok": false, "error":
/// the message} for a document that is not a valid recording (an answer,
/// as for an impossible incision, not a bad request).
nlohmann::json recording_check_answer(const nlohmann::json& doc);
} // namespace breastsim::app
