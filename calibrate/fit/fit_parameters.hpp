#pragma once
// The parameters a calibration fits (--fit mu,c,R,...): their case keys,
// their search bounds, and the log-space coordinates the optimiser works in,
//   y = ln(p),   p = exp(y),
// so that every parameter stays positive and relative steps are uniform.
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
};

/// Short names accepted by --fit and their case keys.
const std::vector<std::pair<std::string, std::string>>& fit_names();

/// Parse "mu,c,R" into parameters with bounds around the case's values:
/// [p0 / span, p0 * span] for material parameters, [p0 / 1.25, p0 * 1.25] for
/// R and H, clipped to the schema's allowed range. Refuses unknown or
/// repeated names and combinations the data cannot identify (see
/// check_identifiable). Throws InputError.
std::vector<FitParameter> parse_fit(const std::string& list, const Config& start);

/// Density and stiffness only enter the equilibrium through their ratio
/// (divide the energy by rho: W/rho - g.u), so rho cannot be fitted with any
/// stiffness (mu, lambda, mu_s, lambda_s, c). Throws InputError.
void check_identifiable(const std::vector<FitParameter>& fit);

/// Log-space coordinates y = ln(p) of the case's current values.
std::vector<double> to_log(const std::vector<FitParameter>& fit, const Config& c);
/// The case with p = exp(y) set for each fitted parameter (validated).
Config with_parameters(const Config& base, const std::vector<FitParameter>& fit,
                       const std::vector<double>& y);
/// True if R or H is fitted (the mesh changes with the parameters).
bool changes_geometry(const std::vector<FitParameter>& fit);
} // namespace breastsim::calibration
