// SPDX-License-Identifier: LGPL-3.0-or-later
#include "case_options.hpp"
#include "errors.hpp"
#include <fmt/format.h>
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
                         "further postures by chest angle theta (docs/MODEL.md), in [-180, 180]"});
  keys.push_back(choice_key("tissue.formulation",
                            d.formulation == TissueFormulation::mixed ? "mixed" : "displacement",
                            {"displacement", "mixed"},
                            "tissue discretisation: displacement (eq. 5 in u) or mixed (Taylor-Hood "
                            "P2-P1 in u and the pressure p = lambda (J - 1); no volumetric locking; "
                            "needs geometry.order = 2 and tissue.lambda >= tissue.mu; simulate and "
                            "converge only)"));
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
  o.formulation = c.text("tissue.formulation") == "mixed" ? TissueFormulation::mixed
                                                          : TissueFormulation::displacement;
  return o;
}

void check_tissue_formulation(const Config& c)
{
  if (c.text("tissue.formulation") != "mixed")
    return;
  if (c.integer("geometry.order") != 2)
    throw InputError(fmt::format("key 'tissue.formulation' = \"mixed\" is Taylor-Hood P2-P1: it needs "
                                 "geometry.order = 2, got {}", c.integer("geometry.order")));
  // p^2 / (2 lambda) in the energy: lambda = 0 is undefined and a small
  // lambda / mu has no locking to cure (use the displacement formulation).
  const double lambda = c.number("tissue.lambda"), mu = c.number("tissue.mu");
  if (!(lambda >= mu))
    throw InputError(fmt::format("key 'tissue.lambda' = {} with tissue.formulation = \"mixed\": allowed "
                                 "[tissue.mu, 1e10] = [{}, 1e10] Pa (the mixed form is for nearly "
                                 "incompressible tissue; below lambda = mu use the displacement "
                                 "formulation)", lambda, mu));
  if (!c.flag("terms.tissue"))
    throw InputError("key 'terms.tissue' = false with tissue.formulation = \"mixed\": the pressure "
                     "belongs to the tissue term");
  if (c.text("solver.linear") == "amg")
    throw InputError("key 'solver.linear' = \"amg\" with tissue.formulation = \"mixed\": the "
                     "saddle-point system is solved by LU (allowed: auto, direct)");
}
} // namespace breastsim
