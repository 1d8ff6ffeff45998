// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The targets of a plan, read once with their ranges: from the command line
// (`--target [side.]key=value`, lengths with their unit) or from the app's
// JSON ({"left": {"sn_n_mm": 210, "n_imf_mm": 70, "grams": 400,
// "lower_pole": 0.55}, "right": {...}}).
#include "plan_search.hpp"
#include <map>
#include <set>

namespace breastsim::clinic
{
/// Set target `key` (sn_n, n_imf [m], grams [g], lower_pole) of `t` to
/// `value`; InputError naming `name` with the value and the range.
void set_target(PlanTargets& t, const std::string& key, double value, const std::string& name);

/// `[left.|right.]key=value` of the command line into `all` (without a
/// side: both; the sides named go into `named`).
void add_target_text(std::map<std::string, PlanTargets>& all, std::set<std::string>& named, const std::string& item);

/// `[left.|right.]a_deg,s,h,d` of the command line (deg, m): the surgeon's
/// own incision of that breast (or both), evaluated without a search.
void add_incision_text(std::map<std::string, PlanTargets>& all, std::set<std::string>& named, const std::string& item);

/// The app's targets document, lengths in mm.
std::map<std::string, PlanTargets> targets_from_json(const nlohmann::json& j);
} // namespace breastsim::clinic
