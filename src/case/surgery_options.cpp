// SPDX-License-Identifier: LGPL-3.0-or-later
#include "surgery_options.hpp"

namespace breastsim
{
void SurgeryOptions::declare(std::vector<KeyInfo>& keys)
{
  const SurgeryOptions d;
  IncisionSpec::declare(keys);
  keys.push_back(number_key("surgery.max_gap", "m", d.max_gap, 0.0, 0.01,
                            "largest suture gap accepted (the penalty is raised until it is met)",
                            true));
}

SurgeryOptions SurgeryOptions::from(const Config& c)
{
  SurgeryOptions o;
  o.incision = IncisionSpec::from(c);
  o.max_gap = c.number("surgery.max_gap");
  return o;
}
} // namespace breastsim
