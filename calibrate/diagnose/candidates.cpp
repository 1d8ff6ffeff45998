#include "candidates.hpp"
#include "errors.hpp"
#include <fmt/format.h>

namespace breastsim::calibration
{
const std::vector<Candidate>& candidate_library()
{
  static const std::vector<Candidate> lib = {
      {"base_springs", "base.compliance", "m/Pa",
       "the Chassaignac space: the base slides on springs (stiffness c = 1/compliance) instead of "
       "being fixed to the chest",
       5e-6},
      {"skin", "skin.mu", "Pa", "a skin membrane (mu_s, lambda_s, thickness) on the outer surface",
       2e4},
      {"suspensory_ligament", "ligament.k", "Pa/m",
       "suspensory (Cooper's) ligaments: the upper-pole skin is tethered toward its neutral "
       "position",
       2e3},
      {"gland_core", "gland.excess", "1",
       "a stiffer glandular core around the nipple axis (stiffness (1 + m_g) x tissue)", 2.0},
  };
  return lib;
}

const Candidate& candidate(const std::string& name)
{
  std::string names;
  for (const auto& c : candidate_library())
  {
    if (c.name == name)
      return c;
    names += (names.empty() ? "" : ", ") + c.name;
  }
  throw InputError(fmt::format("unknown candidate physics '{}' (allowed: {})", name, names));
}

bool Candidate::applicable(const Config& c) const
{
  if (name == "base_springs")
    return c.flag("base.fixed") || !c.flag("terms.base_springs");
  return !c.flag("terms." + name);
}

Config Candidate::with(const Config& current, double q) const
{
  if (!(q > 0))
    throw std::invalid_argument(fmt::format("candidate '{}': q = {} must be > 0", name, q));
  Config c = current;
  c.set("terms." + name, true);
  if (name == "base_springs")
  {
    c.set("base.fixed", false);
    c.set("base.c", 1.0 / q);
  }
  else if (name == "skin")
  {
    const double ratio = current.number("skin.lambda") / current.number("skin.mu");
    c.set("skin.mu", q);
    c.set("skin.lambda", ratio * q);
  }
  else
    c.set(parameter, q);
  c.validate();
  return c;
}
} // namespace breastsim::calibration
