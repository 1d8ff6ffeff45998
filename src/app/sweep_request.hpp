// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A small sweep around a plan, as a job: {"kind": "sweep", "overrides":
// {...}, "vary": {"a": [25, 30, 35], "h": [0.02, 0.025, 0.03]}}: one or two
// of the incision's a, s, h, d (short names or case keys), each with 1 to 3
// values, checked as `breastsim sweep --vary` parses them (the key's type)
// and in the key's range before any job, solved by the library's sweep() on the job's case.
#include "config.hpp"
#include "sweep.hpp"
#include <nlohmann/json.hpp>

namespace breastsim::app
{
/// The grid of `vary` on `base`; InputError naming the field otherwise.
SweepGrid sweep_grid(const nlohmann::json& vary, const Config& base);
/// The number of combinations of a checked `vary`.
std::size_t sweep_size(const nlohmann::json& vary);
} // namespace breastsim::app
