// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A case from a request: JSON {key: value} overrides on the defaults, each
// value set through Config::set_text (the same parse and messages as
// `--set key=value`), then Config::validate. Keys that would let a request
// name files are refused (solver.petsc_options, and every path key such as
// geometry.mesh_file: checked before anything looks at the file system).
#include "config.hpp"
#include <nlohmann/json.hpp>

namespace breastsim::app
{
/// Throws InputError with the CLI's message (key, value, allowed range).
Config case_from_overrides(const nlohmann::json& overrides);
/// Number of postures the case solves (named + by angle).
std::size_t posture_count(const Config& c);
} // namespace breastsim::app
