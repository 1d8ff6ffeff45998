// SPDX-License-Identifier: LGPL-3.0-or-later
#include "solver_options.hpp"

namespace breastsim
{
namespace
{
/// Newton's keys before the coarse start's: linear solver, tolerances,
/// preconditioner reuse, inexact Newton.
void declare_newton_keys(std::vector<KeyInfo>& keys)
{
  const NewtonOptions d;
  keys.push_back(choice_key("solver.linear", d.linear, {"auto", "direct", "amg"},
                            "linear solver: direct (MUMPS LU), amg (GMRES + GAMG with rigid-body "
                            "near nullspace), auto (direct up to solver.direct_max_dofs unknowns)"));
  keys.push_back(choice_key("solver.amg_fine_smoother", d.amg_fine_smoother, {"sor", "chebyshev"},
                            "smoother on the finest AMG level: sor (one symmetric Gauss-Seidel "
                            "sweep) or chebyshev (GAMG's default Chebyshev/Jacobi; -mg_levels_* "
                            "options then reach the finest level too)"));
  keys.push_back(choice_key("solver.amg_cycle", d.amg_cycle, {"w", "v"},
                            "multigrid cycle of the AMG preconditioner: w (coarse levels visited "
                            "twice per level; fewer Krylov iterations on large meshes) or v"));
  keys.push_back(integer_key("solver.direct_max_dofs", d.direct_max_dofs, 0, 1e9,
                             "largest problem solved directly by 'auto' (AMG is faster beyond, "
                             "docs/PERFORMANCE.md)"));
  keys.push_back(number_key("solver.rtol", "1", d.rtol, 0.0, 1e-2,
                            "Newton tolerance on the residual norm relative to the full external "
                            "load",
                            true));
  keys.push_back(number_key("solver.atol", "N", d.atol, 0.0, 1.0,
                            "absolute Newton tolerance on the residual norm"));
  keys.push_back(boolean_key("solver.reuse_preconditioner", d.reuse_preconditioner,
                             "keep the LU factors / AMG hierarchy of an earlier Jacobian while "
                             "Krylov iterations stay few (rebuilt automatically)"));
  keys.push_back(boolean_key("solver.inexact_newton", d.inexact,
                             "solve each Newton system only to the Eisenstat-Walker tolerance "
                             "(loose far from the solution, tight near it); false: to 1e-10 "
                             "(direct) / 1e-8 (amg)"));
  keys.push_back(number_key("solver.forcing_max", "1", d.forcing_max, 0.0, 0.99,
                            "loosest linear tolerance of the inexact Newton method", true));
}
} // namespace

NewtonOptions NewtonOptions::from(const Config& c)
{
  NewtonOptions o;
  o.linear = c.text("solver.linear");
  o.amg_fine_smoother = c.text("solver.amg_fine_smoother");
  o.amg_cycle = c.text("solver.amg_cycle");
  o.direct_max_dofs = c.integer("solver.direct_max_dofs");
  o.rtol = c.number("solver.rtol");
  o.atol = c.number("solver.atol");
  o.max_iterations = static_cast<int>(c.integer("solver.max_iterations"));
  o.reuse_preconditioner = c.flag("solver.reuse_preconditioner");
  o.inexact = c.flag("solver.inexact_newton");
  o.forcing_max = c.number("solver.forcing_max");
  return o;
}

void CoarseStartOptions::declare(std::vector<KeyInfo>& keys)
{
  const CoarseStartOptions d;
  keys.push_back(boolean_key("solver.coarse_start", d.enabled,
                             "grid sequencing: solve each posture first on a coarse P1 mesh "
                             "(solver.coarse_mesh_size; for P2 cases then on up to "
                             "solver.nested_levels P2 meshes) and start Newton from the finest "
                             "one's interpolant, when the mesh has at least 4x the coarse "
                             "unknowns (docs/PERFORMANCE.md); not used with geometry.mesh_file"));
  keys.push_back(number_key("solver.coarse_mesh_size", "m", d.mesh_size, 0.0, 0.1,
                            "mesh size of the coarse mesh of solver.coarse_start", true));
  keys.push_back(number_key("solver.coarse_rtol", "1", d.rtol, 0.0, 1e-2,
                            "Newton tolerance (relative to the load) of the coarse start's "
                            "levels: they only provide the fine Newton's start",
                            true));
  keys.push_back(integer_key("solver.nested_levels", d.nested_levels, 0, 4,
                             "P2 cases with solver.coarse_start: at most this many intermediate "
                             "P2 meshes between the coarse P1 mesh and the case's (mesh size "
                             "doubled per level), each used when it has at least 4x the coarse "
                             "unknowns"));
}

CoarseStartOptions CoarseStartOptions::from(const Config& c)
{
  CoarseStartOptions o;
  o.enabled = c.flag("solver.coarse_start");
  o.mesh_size = c.number("solver.coarse_mesh_size");
  o.rtol = c.number("solver.coarse_rtol");
  o.nested_levels = static_cast<int>(c.integer("solver.nested_levels"));
  return o;
}

void LoadStepOptions::declare(std::vector<KeyInfo>& keys)
{
  const LoadStepOptions d;
  keys.push_back(number_key("solver.initial_load_step", "1", d.initial_step, 0.0, 1.0,
                            "first load increment (fraction of the full load)", true));
  keys.push_back(number_key("solver.min_load_step", "1", d.min_step, 0.0, 1.0,
                            "smallest load increment before giving up", true));
}

LoadStepOptions LoadStepOptions::from(const Config& c)
{
  LoadStepOptions o;
  o.initial_step = c.number("solver.initial_load_step");
  o.min_step = c.number("solver.min_load_step");
  return o;
}

void SolverOptions::declare(std::vector<KeyInfo>& keys)
{
  const SolverOptions d;
  declare_newton_keys(keys);
  CoarseStartOptions::declare(keys);
  keys.push_back(integer_key("solver.max_iterations", d.newton.max_iterations, 1, 1000,
                             "Newton iterations per load step"));
  LoadStepOptions::declare(keys);
  keys.push_back(text_key("solver.petsc_options", d.petsc_options,
                          "extra PETSc options, e.g. \"-ksp_type gmres -pc_type hypre\" "
                          "(override ours)"));
}

SolverOptions SolverOptions::from(const Config& c)
{
  SolverOptions o;
  o.newton = NewtonOptions::from(c);
  o.coarse_start = CoarseStartOptions::from(c);
  o.load_steps = LoadStepOptions::from(c);
  o.petsc_options = c.text("solver.petsc_options");
  return o;
}
} // namespace breastsim
