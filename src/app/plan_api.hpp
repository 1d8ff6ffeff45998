// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The planning requests answered at once (no solve): the case-key schema,
// a check of case overrides, the incision points and planes for (a, s, h, d)
// on the case's cap, and a check of patient measurements. Each throws
// InputError with the library's message (the CLI's) when the input is wrong.
#include <nlohmann/json.hpp>

namespace breastsim::app
{
/// Every case key: key, type, unit, default, lo, hi, lo_open, hi_open,
/// choices, allowed (in words), doc.
nlohmann::json keys_document();
/// {"ok": true, "case_toml": the resolved case} for valid overrides.
nlohmann::json validate_overrides(const nlohmann::json& overrides);
/// A, B, C, D [m], the planes P1, P2 (normal, offset; n . p = offset, n into
/// the kept body) and the cap (R, H) for the incision keys of `overrides`
/// ("ok": true); InputError naming the parameter if the incision does not
/// exist on the cap.
nlohmann::json incision_document(const nlohmann::json& overrides);
/// incision_document, or {"ok": false, "error": the reason} for a valid case
/// whose incision does not exist (an answer, not a bad request).
nlohmann::json check_incision(const nlohmann::json& overrides);
/// The measurements document checked as `calibrate` reads it: its postures
/// and measured quantities.
nlohmann::json check_measurements(const nlohmann::json& doc);
} // namespace breastsim::app
