// SPDX-License-Identifier: LGPL-3.0-or-later
#include "newton.hpp"
#include "log.hpp"
#include "timer.hpp"
#include <algorithm>
#include <cmath>
#include <dolfinx/la/petsc.h>
#include <fmt/format.h>

namespace breastsim
{
namespace
{
/// Run f, timed as `task` (also in dolfinx's timing table); its wall time [s].
template <typename F>
double timed(const std::string& task, F&& f)
{
  Stopwatch clock(task);
  f();
  return clock.seconds();
}
} // namespace

std::string resolved_linear_solver(const NewtonOptions& o, std::int64_t dofs)
{
  if (o.linear != "auto")
    return o.linear;
  return dofs <= o.direct_max_dofs ? "direct" : "amg";
}

NewtonSolver::NewtonSolver(Model& model, NewtonOptions options)
    : _model(model), _opt(std::move(options)), _A(_model.create_matrix()),
      _r(_model.create_vector()), _du(_model.create_vector()), _u0(_model.create_vector()),
      _lin(_model.create_vector())
{
  // The mixed formulation's saddle-point system: LU (no AMG for it here).
  _linear = _model.mixed() ? "direct" : resolved_linear_solver(_opt, _model.num_dofs());
  setup_ksp();
}

NewtonSolver::~NewtonSolver() = default;

void NewtonSolver::setup_ksp()
{
  PETSC_CHECK(KSPCreate(_model.mesh().mesh->comm(), _ksp.out()));
  KSP ksp = _ksp.get();
  PETSC_CHECK(KSPSetOperators(ksp, _A.get(), _A.get()));
  PC pc;
  PETSC_CHECK(KSPGetPC(ksp, &pc));
  if (_linear == "direct")
  {
    // LU (MUMPS) of the current or of an earlier Jacobian, inside GMRES so
    // that a reused factorisation still gives an exact Newton direction.
    PETSC_CHECK(KSPSetType(ksp, _opt.reuse_preconditioner ? KSPGMRES : KSPPREONLY));
    PETSC_CHECK(KSPSetPCSide(ksp, PC_RIGHT));
    PETSC_CHECK(KSPSetTolerances(ksp, 1e-10, 1e-50, 1e8, 60));
    PETSC_CHECK(PCSetType(pc, PCLU));
    PETSC_CHECK(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  }
  else
  {
    // GMRES + smoothed-aggregation AMG. Not CG: far from equilibrium the
    // tangent is indefinite where the relaxed skin and tissue are compressed,
    // and there CG stops (indefinite matrix or preconditioner: the Chebyshev
    // smoothers' eigenvalue estimates assume SPD), e.g. at the first load
    // step on 2 ranks and for P2. GMRES (right preconditioned, so the
    // tolerance is on the true residual) solves the indefinite systems too;
    // whether the direction descends is checked by the Newton loop, which
    // shifts the diagonal if not. The rigid-body modes of the displacement
    // dofs are the near-nullspace (block size 3), the interpolation is reused
    // across Newton iterations (the sparsity never changes).
    PETSC_CHECK(KSPSetType(ksp, KSPGMRES));
    PETSC_CHECK(KSPGMRESSetRestart(ksp, 100));
    PETSC_CHECK(KSPSetPCSide(ksp, PC_RIGHT));
    PETSC_CHECK(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
    PETSC_CHECK(KSPSetTolerances(ksp, 1e-8, 1e-50, 1e8, 1000));
    PETSC_CHECK(PCSetType(pc, PCGAMG));
    PETSC_CHECK(PCGAMGSetReuseInterpolation(pc, PETSC_TRUE));
    // Plain (unsmoothed) aggregation and a small drop threshold: the
    // smoothed prolongator's set-up costs more than its fewer Krylov
    // iterations save (docs/PERFORMANCE.md, "Figures moved from code comments").
    PETSC_CHECK(PCGAMGSetNSmooths(pc, 0));
    PetscReal threshold[] = {0.02};
    PETSC_CHECK(PCGAMGSetThreshold(pc, threshold, 1));
    set_near_nullspace();
  }
  PETSC_CHECK(KSPSetFromOptions(ksp)); // --petsc-options override the defaults above
}

void NewtonSolver::set_near_nullspace()
{
  using PetscNullSpace = PetscOwned<MatNullSpace, MatNullSpaceDestroy>;
  auto V = _model.space();
  const std::vector<double> X = V->tabulate_dof_coordinates(false);
  const std::int32_t n = V->dofmap()->index_map->size_local();
  PetscVec coords;
  PETSC_CHECK(VecCreateMPI(_model.mesh().mesh->comm(), 3 * n, PETSC_DETERMINE, coords.out()));
  PETSC_CHECK(VecSetBlockSize(coords.get(), 3));
  PetscScalar* c;
  PETSC_CHECK(VecGetArray(coords.get(), &c));
  std::copy_n(X.begin(), 3 * n, c);
  PETSC_CHECK(VecRestoreArray(coords.get(), &c));
  PetscNullSpace ns;
  PETSC_CHECK(MatNullSpaceCreateRigidBody(coords.get(), ns.out()));
  PetscInt bs;
  PETSC_CHECK(MatGetBlockSize(_A.get(), &bs));
  log::debug("amg: matrix block size {}, rigid-body near-nullspace on {} local nodes", bs, n);
  PETSC_CHECK(MatSetNearNullSpace(_A.get(), ns.get()));
}

// The AMG levels, once GAMG has built them (the number of levels is only
// known after the set-up; GAMG keeps them while it reuses the interpolation,
// and the checks below re-apply the choices if not).
//
// Cycle (solver.amg_cycle, default w). GAMG's first, aggressive coarsening
// (squared graph) leaves large aggregates, and with plain aggregation the
// coarse-grid correction is the weak part of the V-cycle; a W-cycle visits
// each coarse level twice per visit of the next finer one, which costs
// little (they are over 10x smaller) and reduces the Krylov iterations as
// the mesh grows. A -pc_mg_cycle_type given through --petsc-options wins.
//
// Finest smoother (solver.amg_fine_smoother). With GAMG's default there, two
// Chebyshev iterations preconditioned by Jacobi, the residual reduction per
// GMRES iteration degrades with the mesh; one symmetric Gauss-Seidel sweep
// (SSOR, omega 1; Richardson, no eigenvalue estimate) costs about as much
// and needs far fewer Krylov iterations.
// Only the finest level: on coarse levels (6 rigid-mode unknowns per
// aggregate) PETSc's SOR can stop with a zero pivot in its inode block
// inversion (never on the finest).
// Measurements of both choices: docs/PERFORMANCE.md, "Figures moved from
// code comments".
void NewtonSolver::configure_amg_levels()
{
  PC pc;
  PETSC_CHECK(KSPGetPC(_ksp.get(), &pc));
  PetscBool is_gamg;
  PETSC_CHECK(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCGAMG, &is_gamg));
  if (!is_gamg) // --petsc-options chose another preconditioner
    return;
  PetscInt levels = 0;
  PETSC_CHECK(PCMGGetLevels(pc, &levels));
  if (levels < 2)
    return;
  const char* prefix = nullptr;
  PETSC_CHECK(PCGetOptionsPrefix(pc, &prefix));
  PetscBool cycle_option = PETSC_FALSE;
  PETSC_CHECK(PetscOptionsHasName(nullptr, prefix, "-pc_mg_cycle_type", &cycle_option));
  if (!cycle_option)
    PETSC_CHECK(PCMGSetCycleType(pc, _opt.amg_cycle == "w" ? PC_MG_CYCLE_W : PC_MG_CYCLE_V));

  if (_opt.amg_fine_smoother != "sor")
    return;
  KSP smoother;
  PETSC_CHECK(PCMGGetSmoother(pc, levels - 1, &smoother));
  PetscBool is_richardson;
  PETSC_CHECK(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(smoother), KSPRICHARDSON,
                                     &is_richardson));
  if (is_richardson)
    return;
  PETSC_CHECK(KSPSetType(smoother, KSPRICHARDSON));
  PETSC_CHECK(KSPSetTolerances(smoother, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 1));
  PETSC_CHECK(KSPSetNormType(smoother, KSP_NORM_NONE)); // no residual: PCSOR's Richardson path
  PETSC_CHECK(KSPSetConvergenceTest(smoother, KSPConvergedSkip, nullptr, nullptr));
  PC spc;
  PETSC_CHECK(KSPGetPC(smoother, &spc));
  PETSC_CHECK(PCSetType(spc, PCSOR)); // SOR_LOCAL_SYMMETRIC_SWEEP, omega 1
  log::debug("amg: {}-cycle, finest of {} levels smoothed by one symmetric Gauss-Seidel sweep",
             cycle_option ? "option's" : _opt.amg_cycle, levels);
}

// Eisenstat & Walker (1996), choice 2 with PETSc's constants:
//   eta_k = gamma (|r_k| / |r_k-1|)^alpha, gamma = 0.9, alpha = (1 + sqrt 5) / 2,
// safeguarded by max(eta_k, gamma eta_k-1^alpha) when the latter exceeds 0.1
// (no sudden tightening), and not tighter than needed to reach the Newton
// tolerance, 0.5 tol / |r_k| (Kelley 1995, no over-solving).
// Finishing step: |r_k+1| <= eta_k |r_k| + q_k with the quadratic term
// q_k = |r(u_k + du_k) - r_k - J du_k| predicted from the last full step's
// remainder m_k-1 as q_k ~ m_k-1 (|r_k| / |r_k-1|)^2 (the step shrinks with
// the residual), or bounded by |r_k| (|r_k| / |r_k-1|)^2 when that remainder
// is unknown (m < 0; C |r_k-1|^2 <= |r_k|). When q_k <= tol / 2 the linear
// term is asked for tol / 2 as well (eta_k = 0.5 tol / |r_k|), so that this
// step converges instead of missing the tolerance by a small factor and
// costing one more Jacobian and linear solve.
double eisenstat_walker_forcing(double rnorm, double rnorm_prev, double eta_prev, double tol,
                                double eta_min, double eta_max, double remainder)
{
  const double gamma = 0.9, alpha = 0.5 * (1 + std::sqrt(5.0));
  const double finish = 0.5 * tol / rnorm;
  const double ratio = rnorm / rnorm_prev;
  const double quadratic = (remainder >= 0 ? remainder : rnorm) * ratio * ratio;
  if (ratio < 1 && quadratic <= 0.5 * tol)
    return std::clamp(finish, eta_min, eta_max);
  double eta = gamma * std::pow(ratio, alpha);
  const double guard = gamma * std::pow(eta_prev, alpha);
  if (guard > 0.1)
    eta = std::max(eta, guard);
  eta = std::max(eta, finish);
  return std::clamp(eta, eta_min, eta_max);
}

int NewtonSolver::linear_solve(Vec b, Vec x, double rtol, std::string& msg, bool* indefinite)
{
  if (indefinite)
    *indefinite = false;
  KSP ksp = _ksp.get();
  // A rebuilt preconditioner continues from the iterate of a reused one that
  // ran out of its budget (GMRES minimises the residual: that iterate is no
  // worse than zero), so the iterations already spent are not lost.
  bool continue_from_du = false;
  int total = 0; // Krylov iterations of both attempts
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    const bool fresh = _stale || !_opt.reuse_preconditioner || attempt == 1;
    PETSC_CHECK(KSPSetReusePreconditioner(ksp, fresh ? PETSC_FALSE : PETSC_TRUE));
    PETSC_CHECK(KSPSetInitialGuessNonzero(ksp, continue_from_du ? PETSC_TRUE : PETSC_FALSE));
    // A reused preconditioner gets a short budget: past it, rebuilding is cheaper.
    PETSC_CHECK(KSPSetTolerances(
        ksp, rtol, 1e-50, 1e8, fresh ? 1000 : std::max(_opt.reuse_max_iterations, 2 * _fresh_iterations)));
    if (fresh && _linear == "amg")
    {
      PETSC_CHECK(KSPSetUp(ksp)); // the hierarchy, then its finest smoother
      configure_amg_levels();
    }
    PETSC_CHECK(KSPSolve(ksp, b, x));
    PETSC_CHECK(KSPSetInitialGuessNonzero(ksp, PETSC_FALSE));
    _model.constrain_increment(x);
    KSPConvergedReason reason;
    PETSC_CHECK(KSPGetConvergedReason(ksp, &reason));
    PetscInt its;
    PETSC_CHECK(KSPGetIterationNumber(ksp, &its));
    total += static_cast<int>(its);
    if (fresh)
    {
      ++_setups;
      _stale = false;
      if (!continue_from_du)
        _fresh_iterations = std::max<int>(1, its);
    }
    if (reason > 0)
    {
      msg.clear(); // a failed attempt with the reused preconditioner is not a failure
      return total;
    }
    msg = fmt::format("linear solver failed ({}, {} iterations)", KSPConvergedReasons[reason], its);
    if (indefinite)
      *indefinite = reason == KSP_DIVERGED_INDEFINITE_MAT || reason == KSP_DIVERGED_INDEFINITE_PC;
    if (fresh)
      return -1;
    continue_from_du = reason == KSP_DIVERGED_ITS;
  }
  return -1;
}

void NewtonSolver::assemble_tangent()
{
  _model.assemble_jacobian(_A.get());
  _stale = true;
}

bool NewtonSolver::tangent_solve(Vec b, Vec x, std::string& msg)
{
  return linear_solve(b, x, 1e-12, msg) >= 0;
}

double NewtonSolver::residual_norm()
{
  _model.assemble_residual(_r.get());
  PetscReal n;
  PETSC_CHECK(VecNorm(_r.get(), NORM_2, &n));
  return n;
}

/// The running quantities of one solve.
struct NewtonSolver::State
{
  double tol = 0;        ///< converged when |r| <= tol
  double rnorm = 0;      ///< |r| of the current iterate
  double rnorm_prev = 0; ///< |r| at the previous forcing term
  double energy = 0;     ///< energy of the current iterate
  double eta = 0;        ///< last forcing term
  double remainder = -1; ///< |r(u + du) - r(u) - J du| of the last full step (-1: unknown)
  /// A failed line search after an inexact solve is retried with an exact
  /// one before the solve gives up.
  bool force_exact = false;
};

bool NewtonSolver::stop_test(const State& s, NewtonReport& rep) const
{
  rep.residual_norm = s.rnorm;
  if (!std::isfinite(s.rnorm) || !std::isfinite(s.energy))
  {
    rep.message = "non-finite residual or energy";
    return true;
  }
  rep.converged = s.rnorm <= s.tol;
  return rep.converged;
}

double NewtonSolver::forcing_term(const State& s, int iteration) const
{
  if (!_opt.inexact || s.force_exact)
    return exact_rtol();
  if (iteration == 0)
    return s.eta;
  return eisenstat_walker_forcing(s.rnorm, s.rnorm_prev, s.eta, s.tol, exact_rtol(),
                                  _opt.forcing_max, s.remainder);
}

void NewtonSolver::shift_diagonal(double sigma)
{
  PetscVec d;
  PETSC_CHECK(VecDuplicate(_r.get(), d.out()));
  PETSC_CHECK(MatGetDiagonal(_A.get(), d.get()));
  PETSC_CHECK(VecAbs(d.get()));
  PETSC_CHECK(VecScale(d.get(), sigma));
  PETSC_CHECK(MatDiagonalSet(_A.get(), d.get(), ADD_VALUES));
}

// The Newton direction J du = -r (_r holds -r). An indefinite tangent (a
// compressed region far from equilibrium; CG reports it, LU gives a
// non-descent direction, AMG-preconditioned GMRES may not converge on it)
// has its diagonal shifted, A_ii += sigma |A_ii|, until the direction
// descends (Levenberg-Marquardt style; exact Newton near the solution, where
// the tangent is definite).
NewtonSolver::Direction NewtonSolver::direction(double eta, std::string& msg)
{
  Direction d;
  auto solve_and_test = [&]()
  {
    const int kits = linear_solve(_r.get(), _du.get(), eta, msg);
    d.solved = kits >= 0;
    d.descent = false;
    if (!d.solved)
      return;
    d.linear_iterations += kits;
    PetscScalar dot = 0;
    PETSC_CHECK(VecDot(_r.get(), _du.get(), &dot));
    d.slope = -dot; // dPi/dalpha at alpha = 0: r . du (_r is -r)
    d.descent = d.slope < 0;
  };
  solve_and_test();
  if (_model.mixed())
  {
    d.descent = d.solved; // a saddle point: no descent to test, no shift (see residual_line_search)
    return d;
  }
  for (double sigma = 1e-2; !d.descent && sigma <= 1e2; sigma *= 10)
  {
    d.shifted = true;
    shift_diagonal(sigma);
    _stale = true; // factor the shifted matrix
    PETSC_CHECK(KSPSetOperators(_ksp.get(), _A.get(), _A.get()));
    solve_and_test();
    log::debug("  newton: indefinite tangent, diagonal shift {:.0e}: {}", sigma,
               d.descent ? "descent direction" : "not yet");
  }
  if (d.solved)
    _stale = _stale || d.shifted; // never reuse the factors of a shifted matrix
  return d;
}

double NewtonSolver::backtrack(Vec u, const std::function<bool(double)>& accept)
{
  PETSC_CHECK(VecCopy(u, _u0.get()));
  double step = 2.0;
  for (int k = 0; k <= _opt.max_backtracks; ++k)
  {
    step *= 0.5;
    PETSC_CHECK(VecWAXPY(u, step, _du.get(), _u0.get()));
    _model.set_displacement(u);
    if (_model.min_detF() > 0 && accept(step))
      return step;
  }
  PETSC_CHECK(VecCopy(_u0.get(), u));
  _model.set_displacement(u);
  return 0;
}

// Accept an Armijo energy decrease, or (energy change at round-off level) a
// smaller residual.
double NewtonSolver::line_search(Vec u, double slope, State& s)
{
  return backtrack(u, [&](double step)
  {
    const double e = _model.energy();
    if (!std::isfinite(e))
      return false;
    const double tiny = 1e-12 * std::max(std::abs(s.energy), std::abs(e));
    const bool accepted = e <= s.energy + 1e-4 * step * slope // Armijo
                          || (std::abs(e - s.energy) <= tiny && residual_norm() < s.rnorm);
    if (accepted)
      s.energy = e;
    return accepted;
  });
}

NewtonSolver::Outcome NewtonSolver::iterate(Vec u, State& s, NewtonReport& rep, NewtonRecord& record)
{
  const double t_jacobian = timed("newton: jacobian", [&] { _model.assemble_jacobian(_A.get()); });
  Direction d;
  bool track_remainder = false;
  const double t_linear = timed("newton: direction", [&] {
    PETSC_CHECK(KSPSetOperators(_ksp.get(), _A.get(), _A.get()));
    PETSC_CHECK(VecScale(_r.get(), -1.0));
    s.eta = record.eta = forcing_term(s, rep.iterations);
    s.rnorm_prev = s.rnorm;
    d = direction(s.eta, rep.message);
    // Linear residual -(r + J du) of this step, for the remainder of a full
    // step that predicts whether the next step can finish (forcing term).
    // Only in the fast phase (eta < 0.1): one matrix-vector product.
    track_remainder = d.solved && d.descent && _opt.inexact && !d.shifted && s.eta < 0.1;
    if (track_remainder)
    {
      PETSC_CHECK(MatMult(_A.get(), _du.get(), _lin.get()));
      PETSC_CHECK(VecAYPX(_lin.get(), -1.0, _r.get()));
    }
  });
  rep.linear_iterations += d.linear_iterations;
  record.linear_iterations = d.linear_iterations;
  if (!d.solved)
    return Outcome::stop; // the linear solver's message
  if (!d.descent)
  {
    rep.message = "the Newton direction is not a descent direction (indefinite tangent)";
    return Outcome::stop;
  }

  const double t_search = timed("newton: line search", [&] {
    record.step = _model.mixed() ? residual_line_search(u, s.rnorm, s.energy) : line_search(u, d.slope, s);
  });
  if (record.step == 0)
  {
    if (s.eta <= exact_rtol())
    {
      rep.message = "line search failed (no admissible decrease; det F <= 0 or energy increase)";
      return Outcome::stop;
    }
    log::debug("  newton: line search failed after an inexact solve (eta {:.1e}); "
               "retrying with an exact one", s.eta);
    s.force_exact = true;
    s.rnorm = record.residual_norm = residual_norm();
    record.energy = s.energy;
    return Outcome::next;
  }
  s.force_exact = false;
  s.rnorm = record.residual_norm = residual_norm();
  record.energy = s.energy;
  s.remainder = -1;
  if (track_remainder && record.step == 1.0)
  {
    PETSC_CHECK(VecAXPY(_lin.get(), 1.0, _r.get())); // r(u + du) - r(u) - J du
    PETSC_CHECK(VecNorm(_lin.get(), NORM_2, &s.remainder));
  }
  log::debug("  newton {:2d}: |r| = {:.3e}, energy = {:.9e}, step = {:.3g}, ksp its = {} (eta {:.1e}){}; "
             "time: jacobian {:.3f} s, linear {:.3f} s, line search {:.3f} s",
             rep.iterations + 1, s.rnorm, s.energy, record.step, d.linear_iterations, s.eta,
             s.remainder >= 0 ? fmt::format(", remainder {:.1e}", s.remainder) : std::string(),
             t_jacobian, t_linear, t_search);
  return Outcome::next;
}

NewtonReport NewtonSolver::solve(double reference_norm)
{
  NewtonReport rep;
  PetscVec u(dolfinx::la::petsc::create_vector_wrap(*_model.state()->x()));
  State s;
  s.tol = rep.tolerance = std::max(_opt.atol, _opt.rtol * reference_norm);
  s.rnorm = rep.initial_residual_norm = residual_norm();
  s.energy = _model.energy();
  s.rnorm_prev = s.rnorm;
  s.eta = _opt.forcing_max;
  for (rep.iterations = 0; rep.iterations < _opt.max_iterations; ++rep.iterations)
  {
    if (stop_test(s, rep))
      break;
    Stopwatch clock("newton: iteration");
    NewtonRecord record;
    if (iterate(u.get(), s, rep, record) == Outcome::stop)
      break;
    record.seconds = clock.seconds();
    rep.records.push_back(record);
  }
  if (!rep.converged && rep.iterations == _opt.max_iterations && s.rnorm <= s.tol)
  {
    rep.converged = true; // the last allowed iteration reached the tolerance
    rep.residual_norm = s.rnorm;
  }
  if (!rep.converged && rep.message.empty())
    rep.message = fmt::format("no convergence in {} iterations (|r| = {:.3e} > {:.3e})",
                              _opt.max_iterations, s.rnorm, s.tol);
  return rep;
}
} // namespace breastsim
