// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The solver section of the schema: Newton and its linear solver, grid
// sequencing (the coarse start), load stepping and extra PETSc options;
// plain structs that the solvers take, read from a Config.
#include "config.hpp"
#include <cstdint>
#include <string>
#include <vector>

namespace breastsim
{
/// Newton's method and its linear solver (src/solver/newton.hpp).
struct NewtonOptions
{
  std::string linear = "auto";          ///< "direct", "amg" or "auto"
  std::int64_t direct_max_dofs = 20000;  ///< "auto": direct up to this size
  /// Smoother of the finest AMG level: "sor" (one symmetric Gauss-Seidel
  /// sweep, Richardson) or "chebyshev" (GAMG's default, Chebyshev/Jacobi).
  std::string amg_fine_smoother = "sor";
  /// Multigrid cycle of the AMG preconditioner: "w" or "v".
  std::string amg_cycle = "w";
  double rtol = 1e-9;                   ///< residual tolerance relative to the reference norm
  double atol = 1e-11;                  ///< absolute residual tolerance [N]
  int max_iterations = 40;
  int max_backtracks = 12;              ///< line search halvings (no key)
  /// Keep the preconditioner (LU factors or AMG hierarchy) of an earlier
  /// Jacobian while the Krylov solver converges quickly with it.
  bool reuse_preconditioner = true;
  int reuse_max_iterations = 12;        ///< rebuild when a reused solve needs more (no key)
  /// Inexact Newton: solve J du = -r only to the Eisenstat-Walker forcing
  /// tolerance eta_k (loose far from the solution, tight near it) instead of
  /// to linear_rtol at every iteration.
  bool inexact = true;
  double forcing_max = 0.3;             ///< loosest linear tolerance eta_max

  bool operator==(const NewtonOptions&) const = default;
  /// The case's solver.* Newton keys (declared by SolverOptions::declare:
  /// in the schema they enclose the coarse start's keys).
  static NewtonOptions from(const Config& c);
};

/// Grid sequencing (src/solver/coarse_start.hpp).
struct CoarseStartOptions
{
  bool enabled = true;      ///< solver.coarse_start
  double mesh_size = 0.008; ///< solver.coarse_mesh_size: the coarse P1 mesh [m]
  double rtol = 1e-6;       ///< solver.coarse_rtol: Newton tolerance of the levels
  int nested_levels = 2;    ///< solver.nested_levels: intermediate P2 meshes at most

  bool operator==(const CoarseStartOptions&) const = default;
  /// Append solver.coarse_start, solver.coarse_mesh_size, solver.coarse_rtol,
  /// solver.nested_levels (defaults: the initialisers above).
  static void declare(std::vector<KeyInfo>& keys);
  static CoarseStartOptions from(const Config& c);
};

/// Continuation with cut-back (src/solver/load_stepping.hpp).
struct LoadStepOptions
{
  double initial_step = 1.0; ///< first increment (in parameter units / (to - from))
  double min_step = 1.0 / 1024;
  double growth = 2.0;       ///< step growth after an easy success (no key)

  bool operator==(const LoadStepOptions&) const = default;
  /// Append solver.initial_load_step and solver.min_load_step.
  static void declare(std::vector<KeyInfo>& keys);
  static LoadStepOptions from(const Config& c);
};

/// The whole solver section (solver.max_memory_gb is OutputOptions').
struct SolverOptions
{
  NewtonOptions newton;
  CoarseStartOptions coarse_start;
  LoadStepOptions load_steps;
  std::string petsc_options; ///< solver.petsc_options: extra PETSc options (override ours)

  bool operator==(const SolverOptions&) const = default;
  /// Append the section's keys in schema order: Newton's linear solver and
  /// tolerances, the coarse start, Newton's iteration limit, the load
  /// steps, the PETSc options.
  static void declare(std::vector<KeyInfo>& keys);
  static SolverOptions from(const Config& c);
};
} // namespace breastsim
