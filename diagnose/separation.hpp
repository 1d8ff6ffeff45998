// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Candidates the data cannot tell apart. Two refitted candidates A and B
// that both hold every rule are compared by their margins over their
// critical values, m = LR - critical, with Vuong's test for non-nested
// models on the same data: with d_i = r_B,i^2 - r_A,i^2 (whitened
// residuals of the two fits; sum_i d_i = LR_A - LR_B),
//   z = (m_A - m_B) / sqrt(sum_i (d_i - mean d)^2),
// about N(0, 1) when the two fit equally well. Below the separation level
// the accepted A is not named unless B is found too (a later round): the
// hidden physics lies between the two forms and no name is forced. A rival
// that is another form of A's physics (candidates.hpp, family) does not
// set A aside: the physics is named, its form is reported as undecided.
#include "diagnosis.hpp"

namespace breastsim::diagnosis
{
/// z of the accepted fit `a` over the rival `b` (margin_diff = m_A - m_B);
/// +inf when the two fits have the same residuals and a positive margin.
double separation_z(const FitState& a, const FitState& b, double margin_diff);

/// The rivals of round `r` that are other forms of the physics its tested
/// candidate names (candidates.hpp, family).
std::vector<Rival> same_physics_rivals(const Round& r);

/// Moves each accepted term whose round found a rival closer than the
/// separation level, and whose rivals were not found themselves, from
/// d.discovered to d.undecided.
void set_aside_inseparable(Diagnosis& d);
} // namespace breastsim::diagnosis
