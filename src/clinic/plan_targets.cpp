// SPDX-License-Identifier: LGPL-3.0-or-later
#include "plan_targets.hpp"
#include "errors.hpp"
#include "strings.hpp"
#include <cmath>
#include <fmt/format.h>

namespace breastsim::clinic
{
namespace
{
struct Range
{
  double lo, hi, scale; ///< the range in the unit of the message; SI = unit / scale
  const char* unit;
};

const std::map<std::string, Range>& ranges()
{
  static const std::map<std::string, Range> r = {{"sn_n", {15, 45, 100, "cm"}},
                                                 {"n_imf", {3, 25, 100, "cm"}},
                                                 {"grams", {10, 3000, 1, "g"}},
                                                 {"lower_pole", {0.3, 0.8, 1, ""}}};
  return r;
}

double number(const std::string& text, const std::string& name)
{
  try
  {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v))
      return v;
  }
  catch (const std::exception&)
  {
  }
  throw InputError(fmt::format("{} = '{}' is not a number", name, shorten(text)));
}

/// A length with its unit: "21cm", "210mm", "0.21m".
double length(const std::string& text, const std::string& name)
{
  for (const auto& [unit, scale] : {std::pair{"mm", 1e-3}, std::pair{"cm", 1e-2}, std::pair{"m", 1.0}})
  {
    const std::string u = unit;
    if (text.size() > u.size() && text.compare(text.size() - u.size(), u.size(), u) == 0)
      return scale * number(text.substr(0, text.size() - u.size()), name);
  }
  throw InputError(fmt::format("{} = '{}': a length with its unit, e.g. 21cm, 210mm or 0.21m", name, shorten(text)));
}
} // namespace

void set_target(PlanTargets& t, const std::string& key, double value, const std::string& name)
{
  const auto it = ranges().find(key);
  if (it == ranges().end())
    throw InputError(fmt::format("{}: unknown target '{}' (allowed: sn_n, n_imf, grams, lower_pole)", name, key));
  const Range& r = it->second;
  if (!(value * r.scale >= r.lo && value * r.scale <= r.hi))
    throw InputError(fmt::format("{} = {:g} {} is out of range: [{}, {}] {}", name, value * r.scale, r.unit, r.lo,
                                 r.hi, r.unit));
  (key == "sn_n" ? t.sn_n : key == "n_imf" ? t.n_imf : key == "grams" ? t.grams : t.lower_pole) = value;
}

void add_target_text(std::map<std::string, PlanTargets>& all, std::set<std::string>& named, const std::string& item)
{
  const auto eq = item.find('=');
  if (eq == std::string::npos)
    throw InputError(fmt::format("--target '{}': expected [left.|right.]key=value", shorten(item)));
  std::string key = item.substr(0, eq);
  const std::string text = item.substr(eq + 1), name = "--target " + key;
  std::vector<std::string> sides = {"left", "right"};
  if (const auto dot = key.find('.'); dot != std::string::npos)
  {
    sides = {key.substr(0, dot)};
    key = key.substr(dot + 1);
    if (sides[0] != "left" && sides[0] != "right")
      throw InputError(fmt::format("{}: the side must be left or right", name));
    named.insert(sides[0]);
  }
  if (!ranges().count(key))
    throw InputError(fmt::format("{}: unknown target '{}' (allowed: sn_n, n_imf, grams, lower_pole)", name, key));
  double v = key == "sn_n" || key == "n_imf" ? length(text, name)
                                             : number(key == "grams" && text.size() > 1 && text.back() == 'g'
                                                          ? text.substr(0, text.size() - 1)
                                                          : text,
                                                      name);
  for (const auto& side : sides)
    set_target(all[side], key, v, name);
}

void add_incision_text(std::map<std::string, PlanTargets>& all, std::set<std::string>& named, const std::string& item)
{
  std::vector<std::string> sides = {"left", "right"};
  std::string list = item;
  if (const auto dot = item.find('.'); dot != std::string::npos && (item.rfind("left.", 0) == 0 || item.rfind("right.", 0) == 0))
  {
    sides = {item.substr(0, dot)};
    list = item.substr(dot + 1);
    named.insert(sides[0]);
  }
  const auto v = split_list(list);
  if (v.size() != 4)
    throw InputError(fmt::format("--incision '{}': expected [left.|right.]a_deg,s,h,d (deg, m), e.g. 30,0.02,0.025,0.045",
                                 shorten(item)));
  IncisionSpec in;
  in.a_deg = number(v[0], "--incision a_deg");
  in.s = number(v[1], "--incision s");
  in.h = number(v[2], "--incision h");
  in.d = number(v[3], "--incision d");
  for (const auto& side : sides)
    all[side].incision = in;
}

std::map<std::string, PlanTargets> targets_from_json(const nlohmann::json& j)
{
  if (!j.is_object() || j.empty())
    throw InputError("targets: an object {\"left\": {...}, \"right\": {...}} with at least one side");
  std::map<std::string, PlanTargets> all;
  const std::map<std::string, std::pair<std::string, double>> fields = {
      {"sn_n_mm", {"sn_n", 1e-3}}, {"n_imf_mm", {"n_imf", 1e-3}}, {"grams", {"grams", 1}}, {"lower_pole", {"lower_pole", 1}}};
  for (const auto& [side, t] : j.items())
  {
    if (side != "left" && side != "right")
      throw InputError(fmt::format("targets.{}: the side must be left or right", shorten(side)));
    if (!t.is_object() || t.empty())
      throw InputError(fmt::format("targets.{}: an object of targets (sn_n_mm, n_imf_mm, grams, lower_pole)", side));
    for (const auto& [k, v] : t.items())
    {
      const std::string name = "targets." + side + "." + k;
      const auto f = fields.find(k);
      if (f == fields.end())
        throw InputError(fmt::format("{}: unknown target (allowed: sn_n_mm, n_imf_mm, grams, lower_pole)", name));
      if (!v.is_number() || !std::isfinite(v.get<double>()))
        throw InputError(fmt::format("{} = {} is not a number", name, shorten(v.dump())));
      set_target(all[side], f->second.first, f->second.second * v.get<double>(), name);
    }
  }
  return all;
}
} // namespace breastsim::clinic
