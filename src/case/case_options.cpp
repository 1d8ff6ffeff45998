#include "case_options.hpp"
#include <limits>

namespace breastsim
{
void CaseOptions::declare(std::vector<KeyInfo>& keys)
{
  constexpr double inf = std::numeric_limits<double>::infinity();
  const CaseOptions d;
  keys.push_back(text_key("case.name", d.name,
                          "name of the case (reports; default result folder results/<name>): a "
                          "file-name component of 1 to 100 bytes, no '/', '\\', control "
                          "characters, '.' or '..'"));
  HalfCapSpec::declare(keys);
  keys.push_back(boolean_key("base.fixed", d.fixed_base, "clamp the base (u = 0) instead of the spring bed"));
  keys.push_back(number_key("gravity.g", "m/s^2", d.gravity, 0.0, 100.0, "magnitude of gravity"));
  keys.push_back(KeyInfo{"postures.names", KeyType::string_list, "", d.posture_names, -inf, inf,
                         false, {"standing", "supine", "all_fours", "prone"},
                         "named postures to solve (standing: theta = 0, supine: 90, all_fours "
                         "and prone: -90 deg)"});
  keys.push_back(KeyInfo{"postures.theta_deg", KeyType::number_list, "deg", d.posture_angles_deg,
                         -180, 180, false, {},
                         "further postures by chest angle theta (SPEC.md), in [-180, 180]"});
}

CaseOptions CaseOptions::from(const Config& c)
{
  CaseOptions o;
  o.name = c.text("case.name");
  o.geometry = HalfCapSpec::from(c);
  o.fixed_base = c.flag("base.fixed");
  o.gravity = c.number("gravity.g");
  o.posture_names = c.strings("postures.names");
  o.posture_angles_deg = c.numbers("postures.theta_deg");
  return o;
}
} // namespace breastsim
