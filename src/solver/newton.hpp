// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Newton's method for the total energy of a Model: PETSc KSP for the linear
// systems (MUMPS LU or GMRES + GAMG with the rigid-body near-nullspace, any
// PETSc option overrides), and a backtracking line search that never accepts
// an inverted element (det F <= 0) nor an energy increase. For the mixed
// (u, p) formulation (a saddle point): MUMPS LU of the indefinite system,
// no diagonal shift, and the line search on the residual norm.
#include "config.hpp"
#include "model.hpp"
#include "petsc.hpp"
#include "solver_options.hpp"
#include <functional>
#include <string>
#include <vector>

namespace breastsim
{
/// One Newton iteration, as it ended.
struct NewtonRecord
{
  double residual_norm = 0;  ///< |r| after the iteration [N]
  double energy = 0;         ///< the model's total energy after the iteration [J]
  /// Accepted step length (1: full Newton step); 0 when the line search
  /// found no admissible step and the iterate was kept (the iteration is
  /// then repeated with an exact linear solve).
  double step = 0;
  int linear_iterations = 0; ///< Krylov iterations (every attempt and diagonal shift)
  double eta = 0;            ///< forcing term: relative tolerance of the linear solve
  double seconds = 0;        ///< wall time of the iteration [s]
};

struct NewtonReport
{
  bool converged = false;
  int iterations = 0;
  int linear_iterations = 0;
  double residual_norm = 0;
  double initial_residual_norm = 0; ///< |r| at the start [N]
  double tolerance = 0;             ///< max(atol, rtol * reference norm) [N]
  std::string message;
  std::vector<NewtonRecord> records; ///< one per iteration (records.size() == iterations)
};

/// Eisenstat-Walker (1996) forcing term, choice 2, for the linear solve of
/// the Newton iteration with residual norm `rnorm` (previous one `rnorm_prev`,
/// previous forcing `eta_prev`, Newton tolerance `tol`), within [eta_min,
/// eta_max]; 0.5 tol / rnorm when the step is predicted to finish, from the
/// last full step's remainder |r(u + du) - r(u) - J du| (`remainder`; < 0
/// when unknown).
double eisenstat_walker_forcing(double rnorm, double rnorm_prev, double eta_prev, double tol,
                                double eta_min, double eta_max, double remainder = -1);

/// "direct" or "amg": what options.linear means for a problem of `dofs` unknowns.
std::string resolved_linear_solver(const NewtonOptions& options, std::int64_t dofs);

class NewtonSolver
{
public:
  NewtonSolver(Model& model, NewtonOptions options);
  ~NewtonSolver();
  NewtonSolver(const NewtonSolver&) = delete;
  NewtonSolver& operator=(const NewtonSolver&) = delete;

  /// Solve from the model's current displacement. Converged when
  /// |r| <= max(atol, rtol * reference_norm). On failure the displacement is
  /// left at the last accepted iterate.
  NewtonReport solve(double reference_norm);
  /// Euclidean norm of the current residual.
  double residual_norm();
  /// "direct" or "amg": what the linear solver resolved to.
  const std::string& linear_solver() const { return _linear; }
  /// Force a fresh preconditioner at the next linear solve (e.g. when the
  /// state jumps back to the neutral configuration).
  void invalidate_preconditioner() { _stale = true; }
  /// Number of preconditioner set-ups (factorisations / AMG hierarchies).
  int preconditioner_setups() const { return _setups; }
  /// Assemble the tangent K at the model's current state for
  /// tangent_solve() (a fresh preconditioner at its next solve); every Newton
  /// iteration assembles K afresh, so this never disturbs a later solve.
  void assemble_tangent();
  /// Solve K x = b to relative tolerance 1e-12 with the Newton iterations'
  /// linear solver (LU, or GMRES + AMG); constrained rows of x are zeroed.
  /// Returns false (the reason in `msg`) when the solve fails.
  bool tangent_solve(Vec b, Vec x, std::string& msg);

private:
  /// The running quantities of one solve (newton.cpp).
  struct State;
  /// A Newton direction: Krylov iterations spent, whether the last linear
  /// solve succeeded and descends, the slope r . du, and whether the
  /// diagonal was shifted.
  struct Direction
  {
    int linear_iterations = 0;
    bool solved = false;
    bool descent = false;
    double slope = 0;
    bool shifted = false;
  };
  enum class Outcome
  {
    next,  ///< iteration done (recorded), go on
    stop   ///< the solve cannot go on (message set)
  };

  void setup_ksp();
  /// The rigid-body modes of the displacement as the matrix's near-nullspace.
  void set_near_nullspace();
  /// After an AMG set-up: the cycle (amg_cycle) and the finest level's
  /// smoother (amg_fine_smoother).
  void configure_amg_levels();
  /// Solve J x = b with preconditioner reuse; returns the Krylov
  /// iterations, or -1 (message in `msg`) when even a fresh set-up fails.
  int linear_solve(Vec b, Vec x, double rtol, std::string& msg, bool* indefinite = nullptr);
  /// One Newton iteration from the state `s`: Jacobian, forcing term,
  /// direction, line search, acceptance. Fills `record`.
  Outcome iterate(Vec u, State& s, NewtonReport& rep, NewtonRecord& record);
  /// Linear tolerance of this iteration: Eisenstat-Walker, or exact.
  double forcing_term(const State& s, int iteration) const;
  /// Solve for a descent direction, shifting the diagonal of an indefinite
  /// tangent until the direction descends.
  Direction direction(double eta, std::string& msg);
  /// A_ii += sigma |A_ii|.
  void shift_diagonal(double sigma);
  /// Backtracking from u along _du: the first step a = 1, 1/2, ... (at most
  /// max_backtracks halvings) at which det F > 0 everywhere and
  /// `accept(a)` holds (the model then at u + a du), or 0 with u restored.
  double backtrack(Vec u, const std::function<bool(double step)>& accept);
  /// backtrack() with an Armijo energy decrease (energy updated in `s`).
  double line_search(Vec u, double slope, State& s);
  /// The same for a saddle point (the mixed formulation, whose Lagrangian
  /// has no minimum): backtracking on |r| from |r(u)| = rnorm
  /// (newton_saddle.cpp); `energy` set at the accepted step.
  double residual_line_search(Vec u, double rnorm, double& energy);
  /// Top of an iteration: true when the solve stops here (converged, or a
  /// non-finite residual or energy).
  bool stop_test(const State& s, NewtonReport& rep) const;

  Model& _model;
  NewtonOptions _opt;
  std::string _linear;
  PetscMat _A;
  PetscVec _r, _du, _u0;
  PetscVec _lin; ///< linear residual -(r + J du) of the current step
  PetscKsp _ksp; ///< declared last: destroyed first
  bool _stale = true; ///< rebuild the preconditioner at the next solve
  int _setups = 0;
  int _fresh_iterations = 1;
  /// Linear tolerance of an exact Newton step (and the tightest one used).
  double exact_rtol() const { return _linear == "direct" ? 1e-10 : 1e-8; }
};
} // namespace breastsim
