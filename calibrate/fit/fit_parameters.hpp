// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The parameters a calibration fits (--fit mu,c,R,...): their case keys,
// their search bounds, and the log-space coordinates the optimiser works in,
//   y = ln(p),   p = exp(y),
// so that every parameter stays positive and relative steps are uniform.
// The short names (--fit mu,c,R) are declared by the terms in forms/ (FIT,
// and GEOMETRY_FIT for R, H) and read from the generated registry.
#include "breastsim_registry.hpp"
#include "config.hpp"
#include <string>
#include <vector>

namespace breastsim::calibration
{
struct FitParameter
{
  std::string name;  ///< short name used on the command line, e.g. "mu"
  std::string key;   ///< case key, e.g. "tissue.mu"
  std::string unit;
  double lower = 0;  ///< search bounds [unit]
  double upper = 0;
  generated::FitRole role = generated::FitRole::stiffness;
};

/// The --fit name `name` (its case key and role); throws InputError naming
/// the allowed names.
const generated::FitAliasInfo& fit_alias(const std::string& name);
/// Every --fit name, comma separated (help texts and messages).
std::string fit_alias_names();

/// Parse "mu,c,R" into parameters with bounds around the case's values:
/// [p0 / 30, p0 * 30] for stiffnesses and densities, [p0 / 1.25, p0 * 1.25]
/// for the shape (R, H), clipped to the schema's allowed range. Refuses unknown or
/// repeated names and combinations the data cannot identify (see
/// check_identifiable). Throws InputError.
std::vector<FitParameter> parse_fit(const std::string& list, const Config& start);

/// Density and stiffness only enter the equilibrium through their ratio
/// (divide the energy by rho: W/rho - g.u), so a density (rho) cannot be
/// fitted with any stiffness (mu, lambda, mu_s, lambda_s, c). Throws InputError.
void check_identifiable(const std::vector<FitParameter>& fit);

/// Log-space coordinates y = ln(p) of the case's current values.
std::vector<double> to_log(const std::vector<FitParameter>& fit, const Config& c);
/// The case with p = exp(y) set for each fitted parameter (validated).
Config with_parameters(const Config& base, const std::vector<FitParameter>& fit,
                       const std::vector<double>& y);
/// True if R or H is fitted (the mesh changes with the parameters).
bool changes_geometry(const std::vector<FitParameter>& fit);
} // namespace breastsim::calibration
