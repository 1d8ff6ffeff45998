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
/// Bound factor for material parameters and spring stiffness.
constexpr double material_span = 30.0;
/// Bound factor for the neutral shape R, H.
constexpr double geometry_span = 1.25;

bool is_geometry(const std::string& name) { return name == "R" || name == "H"; }
} // namespace

const std::vector<std::pair<std::string, std::string>>& fit_names()
{
  static const std::vector<std::pair<std::string, std::string>> names
      = {{"mu", "tissue.mu"},  {"lambda", "tissue.lambda"}, {"mu_s", "skin.mu"},
         {"lambda_s", "skin.lambda"}, {"c", "base.c"},      {"R", "geometry.R"},
         {"H", "geometry.H"},    {"rho", "tissue.rho"}};
  return names;
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
    auto it = std::find_if(fit_names().begin(), fit_names().end(),
                           [&](const auto& p) { return p.first == name; });
    if (it == fit_names().end())
      throw InputError(fmt::format("--fit: unknown parameter '{}' (allowed: mu, lambda, mu_s, "
                                   "lambda_s, c, R, H, rho)",
                                   name));
    if (!seen.insert(name).second)
      throw InputError(fmt::format("--fit: parameter '{}' is given twice", name));
    const KeyInfo& k = key_info(it->second);
    const double p0 = start.number(k.key);
    if (!(p0 > 0))
      throw InputError(fmt::format("--fit {}: the starting value {} = {} must be > 0 (the fit "
                                   "works with ln({}))",
                                   name, k.key, p0, name));
    const double span = is_geometry(name) ? geometry_span : material_span;
    // Stay strictly inside the schema's range (open lower bounds, e.g. (0, ...]).
    const double lo = std::max(p0 / span, k.lo > 0 ? k.lo * (1 + 1e-9) : 0.0);
    const double hi = std::min(p0 * span, k.hi);
    fit.push_back({name, k.key, k.unit, lo, hi});
  }
  if (fit.empty())
    throw InputError("--fit: no parameter given (e.g. --fit mu,c)");
  check_identifiable(fit);
  return fit;
}

void check_identifiable(const std::vector<FitParameter>& fit)
{
  const bool rho = std::any_of(fit.begin(), fit.end(), [](const auto& p) { return p.name == "rho"; });
  for (const auto& p : fit)
    if (rho && p.name != "rho" && !is_geometry(p.name))
      throw InputError(fmt::format(
          "--fit: 'rho' and '{}' cannot be fitted together: gravity shapes depend only on the "
          "ratio of stiffness to density (dividing the energy by rho leaves W/rho - g.u), so only "
          "{}/rho is identifiable. Keep tissue.rho as a measured input and fit the stiffnesses",
          p.name, p.name));
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
  return std::any_of(fit.begin(), fit.end(), [](const auto& p) { return is_geometry(p.name); });
}
} // namespace breastsim::calibration
