// SPDX-License-Identifier: LGPL-3.0-or-later
#include "fit_parameters.hpp"
#include "errors.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <set>
#include <sstream>

namespace breastsim::calibration
{
namespace
{
/// Bound factor for stiffnesses and densities.
constexpr double material_span = 30.0;
/// Bound factor for the neutral shape R, H.
constexpr double geometry_span = 1.25;

bool is_shape(const FitParameter& p) { return p.role == generated::FitRole::shape; }
} // namespace

std::string fit_alias_names()
{
  std::string names;
  for (const auto& a : generated::fit_aliases())
    names += (names.empty() ? "" : ", ") + a.alias;
  return names;
}

const generated::FitAliasInfo& fit_alias(const std::string& name)
{
  for (const auto& a : generated::fit_aliases())
    if (a.alias == name)
      return a;
  throw InputError(
      fmt::format("--fit: unknown parameter '{}' (allowed: {})", name, fit_alias_names()));
}

std::vector<FitParameter> parse_fit(const std::string& list, const Config& start)
{
  std::vector<FitParameter> fit;
  std::stringstream ss(list);
  std::string name;
  std::set<std::string> seen;
  while (std::getline(ss, name, ','))
  {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    const generated::FitAliasInfo& alias = fit_alias(name);
    if (!seen.insert(name).second)
      throw InputError(fmt::format("--fit: parameter '{}' is given twice", name));
    const KeyInfo& k = key_info(alias.key);
    const double p0 = start.number(k.key);
    if (!(p0 > 0))
      throw InputError(fmt::format("--fit {}: the starting value {} = {} must be > 0 (the fit "
                                   "works with ln({}))",
                                   name, k.key, p0, name));
    const double span = alias.role == generated::FitRole::shape ? geometry_span : material_span;
    // Stay strictly inside the schema's range (open lower bounds, e.g. (0, ...]).
    const double lo = std::max(p0 / span, k.lo > 0 ? k.lo * (1 + 1e-9) : 0.0);
    const double hi = std::min(p0 * span, k.hi);
    fit.push_back({name, k.key, k.unit, lo, hi, alias.role});
  }
  if (fit.empty())
    throw InputError("--fit: no parameter given (e.g. --fit mu,c)");
  check_identifiable(fit);
  return fit;
}

void check_identifiable(const std::vector<FitParameter>& fit)
{
  const auto density = std::find_if(fit.begin(), fit.end(), [](const auto& p)
                                    { return p.role == generated::FitRole::density; });
  if (density == fit.end())
    return;
  for (const auto& p : fit)
    if (p.role == generated::FitRole::stiffness)
      throw InputError(fmt::format(
          "--fit: '{}' and '{}' cannot be fitted together: gravity shapes depend only on the "
          "ratio of stiffness to density (dividing the energy by {} leaves W/{} - g.u), so only "
          "{}/{} is identifiable. Keep {} as a measured input and fit the stiffnesses",
          density->name, p.name, density->name, density->name, p.name, density->name,
          density->key));
}

std::vector<double> to_log(const std::vector<FitParameter>& fit, const Config& c)
{
  std::vector<double> y;
  for (const auto& p : fit)
    y.push_back(std::log(c.number(p.key)));
  return y;
}

Config with_parameters(const Config& base, const std::vector<FitParameter>& fit,
                       const std::vector<double>& y)
{
  Config c = base;
  for (std::size_t i = 0; i < fit.size(); ++i)
    c.set(fit[i].key, std::exp(y[i]));
  c.validate();
  return c;
}

bool changes_geometry(const std::vector<FitParameter>& fit)
{
  return std::any_of(fit.begin(), fit.end(), is_shape);
}
} // namespace breastsim::calibration
