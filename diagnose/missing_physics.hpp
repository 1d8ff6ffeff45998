// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// After the rounds of a diagnosis, when a misfit remains: the missing
// physics constructed rather than chosen (docs/DISCOVERY.md).
#include "diagnosis.hpp"
#include "fit_state.hpp"
#include "point_evaluator.hpp"
#include <vector>

namespace breastsim::diagnosis
{
/// Collective. A stiffness field and a tissue law, each tried on the
/// rounds' fit `state` of `frees` (when o.discover and their switches
/// allow), into d.field and d.law, their fitted cases on the user's mesh
/// (`users`). When both hold their rules, the one that gains more on the
/// held-out postures models the rest; the other is rejected with that
/// reason.
void construct_missing_physics(PointEvaluator& ev, const Recording& rec, const std::vector<Free>& frees,
                               const FitState& state, const DiagnoseOptions& o, const Config& users,
                               Diagnosis& d);
} // namespace breastsim::diagnosis
