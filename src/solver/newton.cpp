#include "newton.hpp"
#include "log.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <dolfinx/la/petsc.h>
#include <fmt/format.h>

namespace breastsim
{
NewtonOptions newton_options(const Config& c)
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

std::string resolved_linear_solver(const NewtonOptions& o, std::int64_t dofs)
{
  if (o.linear != "auto")
    return o.linear;
  return dofs <= o.direct_max_dofs ? "direct" : "amg";
}

NewtonSolver::NewtonSolver(Model& model, NewtonOptions options)
    : _model(model), _opt(std::move(options))
{
  _A = _model.create_matrix();
  _r = _model.create_vector();
  _du = _model.create_vector();
  _u0 = _model.create_vector();
  _lin = _model.create_vector();
  _linear = resolved_linear_solver(_opt, _model.num_dofs());
  setup_ksp();
}

NewtonSolver::~NewtonSolver()
{
  KSPDestroy(&_ksp);
  MatDestroy(&_A);
  VecDestroy(&_r);
  VecDestroy(&_du);
  VecDestroy(&_u0);
  VecDestroy(&_lin);
}

void NewtonSolver::setup_ksp()
{
  KSPCreate(_model.mesh().mesh->comm(), &_ksp);
  KSPSetOperators(_ksp, _A, _A);
  PC pc;
  KSPGetPC(_ksp, &pc);
  if (_linear == "direct")
  {
    // LU (MUMPS) of the current or of an earlier Jacobian, inside GMRES so
    // that a reused factorisation still gives an exact Newton direction.
    KSPSetType(_ksp, _opt.reuse_preconditioner ? KSPGMRES : KSPPREONLY);
    KSPSetPCSide(_ksp, PC_RIGHT);
    KSPSetTolerances(_ksp, 1e-10, 1e-50, 1e8, 60);
    PCSetType(pc, PCLU);
    PCFactorSetMatSolverType(pc, MATSOLVERMUMPS);
  }
  else
  {
    // GMRES + smoothed-aggregation AMG. Not CG: far from equilibrium the
    // tangent is indefinite where the relaxed skin and tissue are compressed,
    // and then CG stops (indefinite matrix or preconditioner: the Chebyshev
    // smoothers' eigenvalue estimates assume SPD), which happened at the first
    // load step on 2 ranks and for P2. GMRES (right preconditioned, so the
    // tolerance is on the true residual) solves the indefinite systems too;
    // whether the direction descends is checked by the Newton loop, which
    // shifts the diagonal if not. The rigid-body modes of the displacement
    // dofs are the near-nullspace (block size 3), the interpolation is reused
    // across Newton iterations (the sparsity never changes).
    KSPSetType(_ksp, KSPGMRES);
    KSPGMRESSetRestart(_ksp, 100);
    KSPSetPCSide(_ksp, PC_RIGHT);
    KSPSetNormType(_ksp, KSP_NORM_UNPRECONDITIONED);
    KSPSetTolerances(_ksp, 1e-8, 1e-50, 1e8, 1000);
    PCSetType(pc, PCGAMG);
    PCGAMGSetReuseInterpolation(pc, PETSC_TRUE);
    // Plain (unsmoothed) aggregation and a small drop threshold: the
    // smoothed prolongator's set-up cost more than its fewer Krylov
    // iterations saved here (52k P1 tets, standing, inexact Newton: 3.8 s vs
    // 6.2 s; 5k P2: 3.5 s vs 4.9 s; docs/PERFORMANCE.md).
    PCGAMGSetNSmooths(pc, 0);
    PetscReal threshold[] = {0.02};
    PCGAMGSetThreshold(pc, threshold, 1);
    auto V = _model.space();
    const std::vector<double> X = V->tabulate_dof_coordinates(false);
    const std::int32_t n = V->dofmap()->index_map->size_local();
    Vec coords;
    VecCreateMPI(_model.mesh().mesh->comm(), 3 * n, PETSC_DETERMINE, &coords);
    VecSetBlockSize(coords, 3);
    PetscScalar* c;
    VecGetArray(coords, &c);
    std::copy_n(X.begin(), 3 * n, c);
    VecRestoreArray(coords, &c);
    MatNullSpace ns;
    MatNullSpaceCreateRigidBody(coords, &ns);
    PetscInt bs;
    MatGetBlockSize(_A, &bs);
    log::debug("amg: matrix block size {}, rigid-body near-nullspace on {} local nodes", bs, n);
    MatSetNearNullSpace(_A, ns);
    MatNullSpaceDestroy(&ns);
    VecDestroy(&coords);
  }
  KSPSetFromOptions(_ksp); // --petsc-options override the defaults above
}

// The AMG levels, once GAMG has built them (the number of levels is only
// known after the set-up; GAMG keeps them while it reuses the interpolation,
// and the checks below re-apply the choices if not).
//
// Cycle (solver.amg_cycle, default w). GAMG's first, aggressive coarsening
// (squared graph: 19428 -> 1002 rows at 5k P2) leaves large aggregates, and
// with plain aggregation the coarse-grid correction is the weak part of the
// V-cycle; a W-cycle visits each coarse level twice per visit of the next
// finer one, which costs little (they are over 10x smaller) and reduces the
// Krylov iterations as the mesh grows (standing posture, single runs: 194k
// P2 tetrahedra 200 -> 154, 194k P1 104 -> 81, 5k P2 87 -> 80;
// docs/PERFORMANCE.md). A -pc_mg_cycle_type given through --petsc-options
// wins.
//
// Finest smoother (solver.amg_fine_smoother). With GAMG's default there, two
// Chebyshev iterations preconditioned by Jacobi, the residual reduction per
// GMRES iteration degrades with the mesh (last Newton solve of the standing
// posture: 0.44 per iteration at 2.5k P1 unknowns, 0.80 at 107k); one
// symmetric Gauss-Seidel sweep (SSOR, omega 1; Richardson, no eigenvalue
// estimate) costs about as much and needs far fewer Krylov iterations:
// 194k P1 tetrahedra 15.6 -> 11.2 s, 52k P2 53.5 -> 46.2 s (benchmark,
// docs/PERFORMANCE.md).
// Only the finest level: on coarse levels (6 rigid-mode unknowns per
// aggregate) PETSc's SOR stops with a zero pivot in its inode block inversion
// (seen with SOR on all levels, and on level 3 of 5 of a 6 mm P2 mesh;
// never on the finest).
void NewtonSolver::configure_amg_levels()
{
  PC pc;
  KSPGetPC(_ksp, &pc);
  PetscBool is_gamg;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCGAMG, &is_gamg);
  if (!is_gamg) // --petsc-options chose another preconditioner
    return;
  PetscInt levels = 0;
  PCMGGetLevels(pc, &levels);
  if (levels < 2)
    return;
  const char* prefix = nullptr;
  PCGetOptionsPrefix(pc, &prefix);
  PetscBool cycle_option = PETSC_FALSE;
  PetscOptionsHasName(nullptr, prefix, "-pc_mg_cycle_type", &cycle_option);
  if (!cycle_option)
    PCMGSetCycleType(pc, _opt.amg_cycle == "w" ? PC_MG_CYCLE_W : PC_MG_CYCLE_V);

  if (_opt.amg_fine_smoother != "sor")
    return;
  KSP smoother;
  PCMGGetSmoother(pc, levels - 1, &smoother);
  PetscBool is_richardson;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(smoother), KSPRICHARDSON, &is_richardson);
  if (is_richardson)
    return;
  KSPSetType(smoother, KSPRICHARDSON);
  KSPSetTolerances(smoother, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 1);
  KSPSetNormType(smoother, KSP_NORM_NONE); // no residual: PCSOR's Richardson path
  KSPSetConvergenceTest(smoother, KSPConvergedSkip, nullptr, nullptr);
  PC spc;
  KSPGetPC(smoother, &spc);
  PCSetType(spc, PCSOR); // SOR_LOCAL_SYMMETRIC_SWEEP, omega 1
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

int NewtonSolver::linear_solve(double rtol, std::string& msg, bool* indefinite)
{
  if (indefinite)
    *indefinite = false;
  // A rebuilt preconditioner continues from the iterate of a reused one that
  // ran out of its budget (GMRES minimises the residual: that iterate is no
  // worse than zero), so the iterations already spent are not lost.
  bool continue_from_du = false;
  int total = 0; // Krylov iterations of both attempts
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    const bool fresh = _stale || !_opt.reuse_preconditioner || attempt == 1;
    KSPSetReusePreconditioner(_ksp, fresh ? PETSC_FALSE : PETSC_TRUE);
    KSPSetInitialGuessNonzero(_ksp, continue_from_du ? PETSC_TRUE : PETSC_FALSE);
    // A reused preconditioner gets a short budget: past it, rebuilding is cheaper.
    KSPSetTolerances(_ksp, rtol, 1e-50, 1e8,
                     fresh ? 1000 : std::max(_opt.reuse_max_iterations, 2 * _fresh_iterations));
    if (fresh && _linear == "amg")
    {
      KSPSetUp(_ksp); // the hierarchy, then its finest smoother
      configure_amg_levels();
    }
    KSPSolve(_ksp, _r, _du);
    KSPSetInitialGuessNonzero(_ksp, PETSC_FALSE);
    _model.constrain_increment(_du);
    KSPConvergedReason reason;
    KSPGetConvergedReason(_ksp, &reason);
    PetscInt its;
    KSPGetIterationNumber(_ksp, &its);
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

double NewtonSolver::residual_norm()
{
  _model.assemble_residual(_r);
  PetscReal n;
  VecNorm(_r, NORM_2, &n);
  return n;
}

NewtonReport NewtonSolver::solve(double reference_norm)
{
  NewtonReport rep;
  Vec u = dolfinx::la::petsc::create_vector_wrap(*_model.displacement()->x());
  const double tol = std::max(_opt.atol, _opt.rtol * reference_norm);
  double rnorm = residual_norm();
  double energy = _model.energy();
  double rnorm_prev = rnorm, eta = _opt.forcing_max;
  double remainder = -1; // |r(u + du) - r(u) - J du| of the last full step (-1: unknown)
  // A failed line search after an inexact solve is retried with an exact
  // one before the solve gives up.
  bool force_exact = false;
  for (rep.iterations = 0; rep.iterations < _opt.max_iterations; ++rep.iterations)
  {
    rep.residual_norm = rnorm;
    if (!std::isfinite(rnorm) || !std::isfinite(energy))
    {
      rep.message = "non-finite residual or energy";
      break;
    }
    if (rnorm <= tol)
    {
      rep.converged = true;
      break;
    }
    // Newton direction: J du = -r.
    auto t0 = std::chrono::steady_clock::now();
    _model.assemble_jacobian(_A);
    auto t1 = std::chrono::steady_clock::now();
    KSPSetOperators(_ksp, _A, _A);
    VecScale(_r, -1.0);
    if (!_opt.inexact || force_exact)
      eta = exact_rtol();
    else if (rep.iterations > 0)
      eta = eisenstat_walker_forcing(rnorm, rnorm_prev, eta, tol, exact_rtol(), _opt.forcing_max,
                                     remainder);
    rnorm_prev = rnorm;
    bool indefinite = false;
    int kits = linear_solve(eta, rep.message, &indefinite);
    auto t2 = std::chrono::steady_clock::now();
    PetscScalar slope = 0; // dPi/dalpha at alpha = 0: r . du (r is negated)
    auto descent = [&]()
    {
      if (kits < 0)
        return false;
      rep.linear_iterations += kits;
      VecDot(_r, _du, &slope);
      slope = -slope;
      return slope < 0;
    };
    bool ok = descent();
    // Indefinite tangent (a compressed region far from equilibrium; CG
    // reports it, LU gives a non-descent direction, AMG-preconditioned GMRES
    // may not converge on it): shift the diagonal,
    // A_ii += sigma |A_ii|, until the direction descends (Levenberg-Marquardt
    // style; exact Newton near the solution, where the tangent is definite).
    bool shifted = false;
    for (double sigma = 1e-2; !ok && sigma <= 1e2; sigma *= 10)
    {
      shifted = true;
      Vec d;
      VecDuplicate(_r, &d);
      MatGetDiagonal(_A, d);
      VecAbs(d);
      VecScale(d, sigma);
      MatDiagonalSet(_A, d, ADD_VALUES);
      VecDestroy(&d);
      _stale = true; // factor the shifted matrix
      KSPSetOperators(_ksp, _A, _A);
      kits = linear_solve(eta, rep.message, &indefinite);
      ok = descent();
      log::debug("  newton: indefinite tangent, diagonal shift {:.0e}: {}", sigma,
                 ok ? "descent direction" : "not yet");
    }
    if (kits < 0)
      break;
    _stale = _stale || shifted; // never reuse the factors of a shifted matrix
    if (!ok)
    {
      rep.message = "the Newton direction is not a descent direction (indefinite tangent)";
      break;
    }

    // Linear residual -(r + J du) of this step, for the remainder of a full
    // step that predicts whether the next step can finish (forcing term).
    // Only in the fast phase (eta < 0.1): one matrix-vector product.
    const bool track_remainder = _opt.inexact && !shifted && eta < 0.1;
    if (track_remainder)
    {
      MatMult(_A, _du, _lin);
      VecAYPX(_lin, -1.0, _r);
    }

    // Backtracking: accept the first step with det F > 0 everywhere and
    // either an Armijo energy decrease, or (energy change at round-off level)
    // a smaller residual.
    VecCopy(u, _u0);
    double step = 2.0;
    bool accepted = false;
    for (int k = 0; k <= _opt.max_backtracks && !accepted; ++k)
    {
      step *= 0.5;
      VecWAXPY(u, step, _du, _u0);
      _model.set_displacement(u);
      if (!(_model.min_detF() > 0))
        continue;
      const double e = _model.energy();
      if (!std::isfinite(e))
        continue;
      const double tiny = 1e-12 * std::max(std::abs(energy), std::abs(e));
      if (e <= energy + 1e-4 * step * slope) // Armijo
        accepted = true;
      else if (std::abs(e - energy) <= tiny)
      {
        const double rn = residual_norm();
        accepted = rn < rnorm;
      }
      if (accepted)
        energy = e;
    }
    if (!accepted)
    {
      VecCopy(_u0, u);
      _model.set_displacement(u);
      if (eta > exact_rtol())
      {
        log::debug("  newton: line search failed after an inexact solve (eta {:.1e}); "
                   "retrying with an exact one", eta);
        force_exact = true;
        rnorm = residual_norm();
        continue;
      }
      rep.message = "line search failed (no admissible decrease; det F <= 0 or energy increase)";
      break;
    }
    force_exact = false;
    rnorm = residual_norm();
    remainder = -1;
    if (track_remainder && step == 1.0)
    {
      VecAXPY(_lin, 1.0, _r); // r(u + du) - r(u) - J du
      VecNorm(_lin, NORM_2, &remainder);
    }
    auto t3 = std::chrono::steady_clock::now();
    auto secs = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    log::debug("  newton {:2d}: |r| = {:.3e}, energy = {:.9e}, step = {:.3g}, ksp its = {} (eta {:.1e}){}; "
               "time: jacobian {:.3f} s, linear {:.3f} s, line search {:.3f} s",
               rep.iterations + 1, rnorm, energy, step, kits, eta,
               remainder >= 0 ? fmt::format(", remainder {:.1e}", remainder) : std::string(),
               secs(t0, t1), secs(t1, t2), secs(t2, t3));
  }
  if (!rep.converged && rep.iterations == _opt.max_iterations && rnorm <= tol)
  {
    rep.converged = true; // the last allowed iteration reached the tolerance
    rep.residual_norm = rnorm;
  }
  if (!rep.converged && rep.message.empty())
    rep.message = fmt::format("no convergence in {} iterations (|r| = {:.3e} > {:.3e})",
                              _opt.max_iterations, rnorm, tol);
  VecDestroy(&u);
  return rep;
}
} // namespace breastsim
