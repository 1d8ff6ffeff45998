// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A plain Newton method for verification problems that bring their own
// forms (MMS, the sphere benchmark): MUMPS LU, full steps halved while the
// residual norm does not decrease. The production solver (newton.hpp) is
// bound to Model and its energy line search; this one only needs a residual
// form R(u; v), its Jacobian and the Dirichlet conditions.
//   J(u_k) du = -R(u_k),  u_{k+1} = u_k + 2^-m du  (smallest m with |R| decreasing)
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <functional>
#include <memory>
#include "petsc.hpp"
#include <vector>

namespace breastsim
{
struct ResidualNewtonOptions
{
  double rtol = 1e-11;        ///< converged when |R| <= rtol * scale
  int max_iterations = 30;
  int max_halvings = 12;
  /// Also stop (stagnation at round-off) when |du| <= step_rtol |u| and
  /// |R| <= accept_rtol * scale; step_rtol = 0: never.
  double step_rtol = 0;
  double accept_rtol = 0;
};

struct ResidualNewtonResult
{
  int iterations = 0;
  double residual = 0;        ///< |R| at the end
  bool lu_failed = false;
};

class ResidualNewton
{
public:
  using T = PetscScalar;
  ResidualNewton(std::shared_ptr<const dolfinx::fem::Form<T>> R,
                 std::shared_ptr<const dolfinx::fem::Form<T>> J,
                 std::shared_ptr<dolfinx::fem::Function<T>> u,
                 std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<T>>> bcs);

  /// |R(u)| with the constrained rows set to u - g (collective).
  double residual_norm();
  /// Newton from the current u; `progress(iteration, |R|)` after each step.
  ResidualNewtonResult solve(double scale, const ResidualNewtonOptions& o,
                             const std::function<void(int, double)>& progress = {});

private:
  /// _A = J(u) with the constrained rows and columns replaced by the identity.
  void assemble_jacobian();
  /// _dx = J^-1 R by the LU solver; false if the factorization failed.
  bool solve_direction();
  /// u -= step dx with step = 1, halved (at most max_halvings times) while
  /// |R| does not fall below r_old; returns |R| at the accepted step.
  double damped_step(double r_old, int max_halvings, double& step);
  /// |step dx| <= step_rtol |u| and |R| <= accept_rtol * scale.
  bool stagnated(double step, double r, double scale, const ResidualNewtonOptions& o) const;

  std::shared_ptr<const dolfinx::fem::Form<T>> _R, _J;
  std::shared_ptr<dolfinx::fem::Function<T>> _u;
  std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<T>>> _bcs;
  PetscMat _A;
  PetscVec _b, _dx, _x; ///< residual, Newton direction, u's values (a wrap)
  PetscKsp _ksp;
};
} // namespace breastsim
