// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The sutures of a full breast (docs/MODEL.md "Full breast and patient scans"):
// the keel faces sewn to each other by the tissue-to-tissue suture
// (forms/tissue_suture.py, faces suture_a -> suture_b, mirror map
// g(x, y, z) = (-x, y, z): f(g(p)) = f(p)) and the P2 face sewn to the chest
// (forms/sutures.py, suture_bcd -> y = 0). Both closures are driven together
// without gravity, then both penalties are raised x10 until the largest gap
// is at most surgery.max_gap.
#include "partner_field.hpp"
#include "surgery.hpp"

namespace breastsim
{
/// The mirror map G = diag(-1, 1, 1), t = 0 set on the tissue suture.
void set_mirror_map(Model& model);

/// Largest |f(X) - f(g(X))| = |X + u - g(X) - w| over the nodes X of face A
/// (suture_a), w = P u the partner field (collective).
double max_tissue_suture_gap(Model& model);

struct FullSutureReport
{
  SutureReport suture;   ///< max_gap: the larger of the two below
  double gap_tissue = 0; ///< keel faces, |f(X) - f(g(X))| [m]
  double gap_chest = 0;  ///< P2 face to the chest plane [m]
  PartnerImageStats images; ///< face A's nodes whose mirror images lie beyond face B's cells
};

/// Close both sutures (tissue_suture and sutures switched on, gravity off
/// during the closure and restored after). SolveError on failure names the
/// fold site and the nearest of `points` (name, position).
FullSutureReport close_full_breast_sutures(Model& model, const Config& c,
                                           const std::vector<std::pair<std::string, std::array<double, 3>>>& points);
} // namespace breastsim
