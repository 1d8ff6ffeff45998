// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Checks of command-line options shared by the subcommands: each throws
// InputError naming the option, the value and what is allowed.
#include "scan_surface.hpp"
#include <string>

namespace breastsim::cli
{
/// "x,y,z" -> three finite numbers; InputError naming `option` otherwise.
scan::Vec3 parse_vector(const std::string& text, const std::string& option);

/// lo <= v <= hi; InputError "OPTION = V is out of range: allowed [LO, HI] UNIT" otherwise.
void check_range(double v, double lo, double hi, const std::string& option, const std::string& unit = "");
} // namespace breastsim::cli
