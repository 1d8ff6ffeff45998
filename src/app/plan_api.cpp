// SPDX-License-Identifier: LGPL-3.0-or-later
#include "plan_api.hpp"
#include "case_request.hpp"
#include "errors.hpp"
#include "measurements.hpp"
#include "geometry_options.hpp"
#include "incision.hpp"
#include <cmath>

namespace breastsim::app
{
namespace
{
nlohmann::json value_json(const Value& v)
{
  return std::visit([](const auto& x) { return nlohmann::json(x); }, v);
}

nlohmann::json bound(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); }
} // namespace

nlohmann::json keys_document()
{
  nlohmann::json keys = nlohmann::json::array();
  for (const auto& k : schema())
    keys.push_back({{"key", k.key}, {"type", type_name(k.type)}, {"unit", k.unit},
                    {"default", value_json(k.default_value)}, {"lo", bound(k.lo)}, {"hi", bound(k.hi)},
                    {"lo_open", k.lo_open}, {"hi_open", k.hi_open}, {"choices", k.choices},
                    {"allowed", range_text(k)}, {"doc", k.doc}});
  return {{"keys", keys}};
}

nlohmann::json validate_overrides(const nlohmann::json& overrides)
{
  const Config c = case_from_overrides(overrides);
  return {{"ok", true}, {"case_toml", c.to_toml()}};
}

nlohmann::json incision_document(const nlohmann::json& overrides)
{
  const Config c = case_from_overrides(overrides);
  const auto cap = HalfCapSpec::from(c);
  const auto g = meshes::incision_geometry(cap, IncisionSpec::from(c));
  return {{"ok", true},
          {"cap", {{"R", cap.R}, {"H", cap.H}}},
          {"A", g.A}, {"B", g.B}, {"C", g.C}, {"D", g.D},
          {"P1", {{"normal", g.n1}, {"offset", g.c1}}},
          {"P2", {{"normal", g.n2}, {"offset", g.c2}}}};
}

nlohmann::json check_incision(const nlohmann::json& overrides)
{
  case_from_overrides(overrides); // a wrong case key: InputError (HTTP 400)
  try
  {
    return incision_document(overrides);
  }
  catch (const InputError& e)
  {
    return {{"ok", false}, {"error", e.what()}};
  }
}

nlohmann::json check_measurements(const nlohmann::json& doc)
{
  const auto m = calibration::parse_measurements(doc, "request");
  nlohmann::json postures = nlohmann::json::array(), items = nlohmann::json::array();
  for (const auto& p : m.postures)
    postures.push_back(p.name);
  for (const auto& i : m.items)
    items.push_back({{"label", i.label}, {"value_m", i.value}, {"sigma_m", i.sigma}});
  return {{"ok", true}, {"postures", postures}, {"measurements", items}};
}
} // namespace breastsim::app
