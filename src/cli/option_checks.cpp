// SPDX-License-Identifier: LGPL-3.0-or-later
#include "option_checks.hpp"
#include "errors.hpp"
#include <cmath>
#include <fmt/format.h>
#include <sstream>

namespace breastsim::cli
{
scan::Vec3 parse_vector(const std::string& text, const std::string& option)
{
  std::istringstream in(text);
  scan::Vec3 v;
  char c1 = 0, c2 = 0;
  if (!(in >> v[0] >> c1 >> v[1] >> c2 >> v[2]) || c1 != ',' || c2 != ',' || !(in >> std::ws).eof() ||
      !std::isfinite(v[0] + v[1] + v[2]))
    throw InputError(fmt::format("{} = '{}': three finite numbers x,y,z are needed", option, text));
  return v;
}

void check_range(double v, double lo, double hi, const std::string& option, const std::string& unit)
{
  if (!(v >= lo && v <= hi))
  {
    const std::string allowed = fmt::format("allowed [{}, {}]", lo, hi);
    throw InputError(fmt::format("{} = {} is out of range: {}{}{}", option, v, allowed, unit.empty() ? "" : " ", unit));
  }
}
} // namespace breastsim::cli
