// SPDX-License-Identifier: LGPL-3.0-or-later
#include "progress.hpp"
#include <algorithm>

namespace breastsim
{
void Progress::report(const std::string& stage, double done) const
{
  if (_callback)
    _callback(_prefix + stage, _from + std::clamp(done, 0.0, 1.0) * (_to - _from));
}

Progress Progress::part(double from, double to, const std::string& prefix) const
{
  Progress p = *this;
  p._from = _from + std::clamp(from, 0.0, 1.0) * (_to - _from);
  p._to = _from + std::clamp(to, 0.0, 1.0) * (_to - _from);
  p._prefix = _prefix + prefix;
  return p;
}
} // namespace breastsim
