#pragma once
// The diagnosis mesh's own discretisation error, measured against a mesh
// `ratio` times finer: the numerical noise floor (sigma_eff), and the
// numerical part of the uncertainty of the found values.
#include "diagnosis.hpp"
#include "point_evaluator.hpp"
#include <vector>

namespace breastsim::calibration
{
/// Case `c` on a mesh `ratio` times finer (validated).
Config finer(const Config& c, double ratio);

/// Numerical noise floor of the diagnosis mesh at the fitted state: the RMS
/// change e_h of each posture's distances (and of each landmark) on a mesh
/// `ratio` times finer; sigma_eff^2 = sigma^2 + e_h^2 per residual (returned)
/// and per posture (d.mesh_error, d.sigma_eff).
std::vector<double> noise_floor(PointEvaluator& ev, PointEvaluator& fine_ev, const Recording& rec,
                                const FitState& state, double ratio, Diagnosis& d);

/// Values and intervals of a found model on the finer mesh, with the
/// numerical part |ln p_h - ln p_{h/r}| / (r - 1) (Richardson, order 1)
/// added in quadrature to the statistical SE of ln p.
FitState with_numerical_uncertainty(const FitState& coarse, const FitState& fine, double ratio,
                                    std::vector<double>& se_numerical);
} // namespace breastsim::calibration
