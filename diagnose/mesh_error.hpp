// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The diagnosis mesh's own discretisation error, measured against a mesh
// `ratio` times finer: the numerical noise floor (sigma_eff), and the
// numerical part of the uncertainty of the found values.
#include "diagnosis.hpp"
#include "point_evaluator.hpp"
#include <vector>

namespace breastsim::diagnosis
{
/// Case `c` on a mesh `ratio` times finer (validated).
Config finer(const Config& c, double ratio);

/// Per-posture floors of which only the `solved` ones were measured: each
/// other takes the largest measured one. False if none was measured.
bool fill_unsolved(std::vector<double>& floor, const std::vector<bool>& solved);

/// Per-point numerical noise floor of one posture, e_h,i: the RMS of the
/// distances' change over point i and its k nearest points.
std::vector<double> local_floor(const std::vector<Point>& pts, const std::vector<double>& change,
                                int k);

/// Numerical noise floor of the diagnosis mesh at the fitted state, from the
/// change of the distances (and of each landmark) on a mesh `o.mesh_ratio`
/// times finer: e_h per posture (RMS change; d.mesh_error, d.sigma_eff) and
/// per point (local_floor; d.local_floor_max); sigma_eff^2 = sigma^2 + e_h^2
/// per residual (returned), each point with its own e_h,i. A posture the finer
/// mesh cannot solve takes the largest posture e_h of the others and is
/// excluded from fine_ev (d.unsolved_on_finer); throws SolveError if none solves.
std::vector<double> noise_floor(PointEvaluator& ev, PointEvaluator& fine_ev, const Recording& rec,
                                const FitState& state, const DiagnoseOptions& o, Diagnosis& d);

/// Values and intervals of a found model: the finer mesh's values (else the
/// diagnosis mesh's) with the numerical part |ln p_h - ln p_{h/r}| / (r - 1)
/// (Richardson, order 1) added in quadrature to the statistical SE of ln p.
/// The diagnosis mesh's values are kept when the finer fit left postures out.
FitState with_numerical_uncertainty(const FitState& coarse, const FitState& fine, double ratio,
                                    bool values_from_fine, std::vector<double>& se_numerical);
} // namespace breastsim::diagnosis
