// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A discovered stiffness field in words: where its extreme lies (breast
// frame, docs/MODEL.md, and clinical words), how much stiffer or softer
// (exp(s) with its 95 % interval), over what region, and which known
// physics it resembles.
#include "diagnosis.hpp"
#include "field_basis.hpp"
#include <string>

namespace breastsim::diagnosis
{
struct FieldSummary
{
  /// exp(median of s over the half cap): the bulk of the tissue is this
  /// many times the fitted mu; the rest is stated relative to it.
  double bulk_factor = 1;
  Point peak{};            ///< where |s - median| is largest [m]
  double factor = 1;       ///< exp(s - median) there
  double factor_lo = 1, factor_hi = 1; ///< its 95 % interval
  Point centroid{};        ///< centroid of the region where s - median has the peak's sign and half its size or more [m]
  std::array<double, 3> extent_mm{}; ///< its extent along x, y, z (the half model's) [mm]
  double volume_share = 0; ///< its share of the half cap's volume
  std::string where;       ///< clinical words
  std::string resembles;   ///< the known physics it looks like
  std::string words;       ///< one sentence
};

/// Samples s on a 2 mm lattice inside the half cap (R, H). cov_a: the
/// amplitudes' covariance (empty: no interval).
FieldSummary summarise_field(const FieldBasis& b, const std::vector<double>& a, const Matrix& cov_a,
                             double R, double H);
} // namespace breastsim::diagnosis
