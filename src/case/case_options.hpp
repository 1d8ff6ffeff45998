// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The case section of the schema: the case's name, its neutral geometry
// (HalfCapSpec), the base condition, gravity and the requested postures.
#include "config.hpp"
#include "geometry_options.hpp"
#include <string>
#include <vector>

namespace breastsim
{
/// How the tissue is discretised (tissue.formulation): the displacement u
/// alone (paper eq. 5; locks as lambda / mu grows at P1), or the mixed
/// Taylor-Hood P2-P1 (u, p) form of the same law (forms/tissue.py).
enum class TissueFormulation
{
  displacement,
  mixed
};

struct CaseOptions
{
  std::string name = "breast"; ///< case.name: reports, default result folder
  HalfCapSpec geometry;        ///< geometry.*
  bool fixed_base = false;     ///< base.fixed: clamped base instead of the spring bed
  double gravity = 9.81;       ///< gravity.g: magnitude of gravity [m/s^2]
  /// postures.names: named postures (standing, supine, all_fours, prone).
  std::vector<std::string> posture_names = {"standing", "supine", "all_fours"};
  std::vector<double> posture_angles_deg; ///< postures.theta_deg: further chest angles [deg]
  TissueFormulation formulation = TissueFormulation::displacement; ///< tissue.formulation

  bool operator==(const CaseOptions&) const = default;
  /// Append case.name, geometry.*, base.fixed, gravity.g, postures.names,
  /// postures.theta_deg, tissue.formulation (defaults: the initialisers above).
  static void declare(std::vector<KeyInfo>& keys);
  static CaseOptions from(const Config& c);
};

/// Cross-key rules of tissue.formulation = mixed (InputError naming the key):
/// geometry.order = 2, tissue.lambda >= tissue.mu, terms.tissue on,
/// solver.linear not amg (the saddle-point system is solved by LU).
void check_tissue_formulation(const Config& c);
} // namespace breastsim
