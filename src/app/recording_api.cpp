// SPDX-License-Identifier: LGPL-3.0-or-later
#include "recording_api.hpp"
#include "errors.hpp"
#include "recording.hpp"
#include <fmt/format.h>

namespace breastsim::app
{
nlohmann::json check_recording(const nlohmann::json& doc)
{
  const auto rec = calibration::parse_recording(doc, "recording");
  std::size_t points = 0;
  auto postures = nlohmann::json::array();
  for (const auto& p : rec.postures)
  {
    points += p.points.size();
    postures.push_back({{"name", p.name}, {"theta_deg", p.theta_deg}, {"points", p.points.size()},
                        {"nipple", p.nipple.has_value()}});
  }
  if (points > max_recording_points)
    throw InputError(fmt::format("recording: {} skin points in all is out of range: allowed [10, {}] "
                                 "(each point is fitted at every evaluation)",
                                 points, max_recording_points));
  return {{"ok", true}, {"noise_sigma_m", rec.noise_sigma}, {"known", rec.known},
          {"points", points}, {"postures", postures}};
}

nlohmann::json recording_check_answer(const nlohmann::json& doc)
{
  try
  {
    return check_recording(doc);
  }
  catch (const InputError& e)
  {
    return {{"ok", false}, {"error", e.what()}};
  }
}
} // namespace breastsim::app
