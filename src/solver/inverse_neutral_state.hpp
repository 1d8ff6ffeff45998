// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The stress-free neutral state of a loaded shape by inverse elastostatics.
// The model's mesh holds the loaded shape x_s (a scan, or a forward solve);
// sought is the reference X that the model's load deforms into it,
//   X + u(X) = x_s   at every mesh node,
// found by the backward-displacement fixed point (Sellier 2011, "An
// iterative method for the inverse elasto-static problem", J. Fluids Struct.
// 27; Bols et al. 2013, J. Comput. Appl. Math. 246)
//   X_{k+1} = X_k + omega_k r_k,   r_k = x_s - X_k - u(X_k),
// with Aitken's dynamic relaxation (Kuettler & Wall 2008, Comput. Mech. 43)
//   omega_k = -omega_{k-1} r_{k-1}.(r_k - r_{k-1}) / |r_k - r_{k-1}|^2.
// Each forward solve starts from the previous u (solve_at_full_load).
#include "load_stepping.hpp"
#include "model.hpp"
#include "newton.hpp"
#include <vector>

namespace breastsim
{
struct InverseOptions
{
  double tolerance = 1e-6; ///< largest node mismatch |x_s - X - u| accepted [m]
  int max_iterations = 60;
  LoadStepOptions ramp;    ///< load ramp of a forward solve that cannot start from the last u
  /// Nodes on the chest plane y = 0 (the base, docs/MODEL.md) stay on it: only
  /// their x and z are updated and measured, so that a spring bed's normal
  /// displacement of the base is not turned into a reference off the chest.
  bool keep_chest_plane = true;
};

struct InverseIteration
{
  double rms_mismatch = 0, max_mismatch = 0; ///< |x_s - X_k - u(X_k)| over the nodes [m]
  double omega = 1;                          ///< relaxation of the update after it
  int newton_iterations = 0;                 ///< of the forward solve
};

struct InverseReport
{
  bool converged = false;
  std::vector<InverseIteration> iterations;
  double seconds = 0;
};

/// Replace the model's mesh geometry (the loaded shape) by the reference
/// that the model's load, at load factor 1, deforms into it; on return u is
/// that deformation. `reference_norm` is the force scale of the Newton
/// tolerance (set_gravity's return). Collective. Throws SolveError naming
/// the iteration when a forward solve fails, when the mismatch grows for
/// three iterations in a row, or when it is not below the tolerance after
/// max_iterations: the material cannot hold the shape under the load, or
/// not within the options.
InverseReport inverse_neutral_state(Model& model, NewtonSolver& newton, const InverseOptions& o,
                                    double reference_norm);
} // namespace breastsim
