// SPDX-License-Identifier: LGPL-3.0-or-later
#include "candidates.hpp"
#include "term_switches.hpp"
#include "errors.hpp"
#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

namespace breastsim::diagnosis
{
const std::vector<Candidate>& candidate_library()
{
  static const std::vector<Candidate> lib = []
  {
    std::vector<Candidate> out;
    for (const auto& c : generated::candidates())
      out.push_back({c.term, c.parameter, c.unit, c.physics, c.typical, c.sets, c.flags, c.family, c.extends,
                     c.in_default_library});
    return out;
  }();
  return lib;
}

namespace
{
// The library's names that satisfy keep, joined by ", ".
template <typename Keep>
std::string joined_names(Keep keep)
{
  std::string names;
  for (const auto& c : candidate_library())
    if (keep(c))
      names += (names.empty() ? "" : ", ") + c.name;
  return names;
}
} // namespace

std::string candidate_names()
{
  return joined_names([](const Candidate&) { return true; });
}

std::string candidates_not_default()
{
  return joined_names([](const Candidate& c) { return !c.in_default_library; });
}

bool is_wanted(const Candidate& c, const std::vector<std::string>& wanted)
{
  return wanted.empty() ? c.in_default_library
                        : std::find(wanted.begin(), wanted.end(), c.name) != wanted.end();
}

std::string candidate_parameters()
{
  std::string s;
  for (const auto& c : candidate_library())
    s += fmt::format("{}{}: {} [{}]", s.empty() ? "" : "; ", c.name, c.parameter, c.unit);
  return s;
}

const Candidate& candidate(const std::string& name)
{
  for (const auto& c : candidate_library())
    if (c.name == name)
      return c;
  throw InputError(
      fmt::format("unknown candidate physics '{}' (allowed: {})", name, candidate_names()));
}

std::vector<std::string> physics_of(const std::vector<std::string>& names)
{
  std::vector<std::string> out;
  for (const auto& n : names)
    if (std::find(out.begin(), out.end(), candidate(n).family) == out.end())
      out.push_back(candidate(n).family);
  return out;
}

int physics_found(const std::vector<std::string>& names)
{
  return static_cast<int>(
      std::count_if(names.begin(), names.end(), [](const auto& n) { return candidate(n).extends.empty(); }));
}

bool Candidate::in_model(const Config& c) const
{
  if (!TermSwitches::from(c).is_on(name))
    return false;
  return std::all_of(flags.begin(), flags.end(),
                     [&c](const auto& f) { return c.flag(f.first) == f.second; });
}

bool Candidate::applicable(const Config& c) const
{
  const TermSwitches on = TermSwitches::from(c);
  if (!extends.empty())
    return candidate(extends).in_model(c) && !on.is_on(name);
  for (const auto& other : candidate_library())
    if (other.name != name && other.extends.empty() && same_physics(other) && on.is_on(other.name))
      return false;
  return !in_model(c);
}

Config Candidate::with(const Config& current, double q) const
{
  if (!(q > 0))
    throw std::invalid_argument(fmt::format("candidate '{}': q = {} must be > 0", name, q));
  Config c = current;
  c.set("terms." + name, true);
  for (const auto& [key, value] : flags)
    c.set(key, value);
  const std::string& first = sets.front().key;
  for (const auto& s : sets)
    switch (s.rule)
    {
    case generated::CandidateRule::value:
      c.set(s.key, q);
      break;
    case generated::CandidateRule::inverse:
      c.set(s.key, 1.0 / q);
      break;
    case generated::CandidateRule::keep_ratio:
    {
      const double ratio = current.number(s.key) / current.number(first);
      c.set(s.key, ratio * c.number(first));
      break;
    }
    }
  c.validate();
  return c;
}
} // namespace breastsim::diagnosis
