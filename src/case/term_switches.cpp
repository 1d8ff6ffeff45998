// SPDX-License-Identifier: LGPL-3.0-or-later
#include "term_switches.hpp"
#include "breastsim_registry.hpp"

namespace breastsim
{
std::map<std::string, bool> TermSwitches::generated_defaults()
{
  std::map<std::string, bool> on;
  for (const auto& t : generated::terms())
    on[t.name] = t.default_on;
  return on;
}

void TermSwitches::declare(std::vector<KeyInfo>& keys)
{
  const TermSwitches d;
  for (const auto& t : generated::terms())
    keys.push_back(boolean_key("terms." + t.name, d.is_on(t.name),
                               "switch the '" + t.name + "' energy term on/off"));
}

TermSwitches TermSwitches::from(const Config& c)
{
  TermSwitches s;
  for (auto& [term, on] : s.on)
    on = c.flag("terms." + term);
  return s;
}
} // namespace breastsim
