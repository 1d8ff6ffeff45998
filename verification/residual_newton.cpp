// SPDX-License-Identifier: LGPL-3.0-or-later
#include "residual_newton.hpp"
#include "ghosted_assembly.hpp"
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/la/petsc.h>

namespace breastsim
{
using namespace dolfinx;

ResidualNewton::ResidualNewton(std::shared_ptr<const fem::Form<T>> R,
                               std::shared_ptr<const fem::Form<T>> J,
                               std::shared_ptr<fem::Function<T>> u,
                               std::vector<std::shared_ptr<const fem::DirichletBC<T>>> bcs)
    : _R(std::move(R)), _J(std::move(J)), _u(std::move(u)), _bcs(std::move(bcs))
{
  auto V = _u->function_space();
  _A = PetscMat(fem::petsc::create_matrix(*_J, "aij"));
  _b = PetscVec(la::petsc::create_vector(*V->dofmap()->index_map, V->dofmap()->index_map_bs()));
  PETSC_CHECK(VecDuplicate(_b.get(), _dx.out()));
  _x = PetscVec(la::petsc::create_vector_wrap(*_u->x()));
  PETSC_CHECK(KSPCreate(V->mesh()->comm(), _ksp.out()));
  PETSC_CHECK(KSPSetType(_ksp.get(), KSPPREONLY));
  PC pc;
  PETSC_CHECK(KSPGetPC(_ksp.get(), &pc));
  PETSC_CHECK(PCSetType(pc, PCLU));
  PETSC_CHECK(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
}

double ResidualNewton::residual_norm()
{
  assemble_ghosted(_b.get(), *_R);
  fem::petsc::set_bc(_b.get(), _bcs, _x.get(), -1.0);
  PetscReal n;
  PETSC_CHECK(VecNorm(_b.get(), NORM_2, &n));
  return double(n);
}

void ResidualNewton::assemble_jacobian()
{
  Mat A = _A.get();
  PETSC_CHECK(MatZeroEntries(A));
  fem::assemble_matrix(la::petsc::Matrix::set_block_fn(A, ADD_VALUES), *_J, _bcs);
  PETSC_CHECK(MatAssemblyBegin(A, MAT_FLUSH_ASSEMBLY));
  PETSC_CHECK(MatAssemblyEnd(A, MAT_FLUSH_ASSEMBLY));
  fem::set_diagonal<T>(la::petsc::Matrix::set_fn(A, INSERT_VALUES), *_u->function_space(), _bcs);
  PETSC_CHECK(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PETSC_CHECK(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
}

bool ResidualNewton::solve_direction()
{
  PETSC_CHECK(KSPSetOperators(_ksp.get(), _A.get(), _A.get()));
  PETSC_CHECK(KSPSolve(_ksp.get(), _b.get(), _dx.get()));
  KSPConvergedReason reason;
  PETSC_CHECK(KSPGetConvergedReason(_ksp.get(), &reason));
  return reason >= 0;
}

double ResidualNewton::damped_step(double r_old, int max_halvings, double& step)
{
  // Full step, halved while the residual norm grows or is not finite
  // (ln J of an inverted trial state).
  step = 1.0;
  PETSC_CHECK(VecAXPY(_x.get(), -step, _dx.get()));
  _u->x()->scatter_fwd();
  double r = residual_norm();
  for (int k = 0; k < max_halvings && !(r < r_old); ++k)
  {
    step *= 0.5;
    PETSC_CHECK(VecAXPY(_x.get(), step, _dx.get())); // back to half of the step tried last
    _u->x()->scatter_fwd();
    r = residual_norm();
  }
  return r;
}

bool ResidualNewton::stagnated(double step, double r, double scale,
                               const ResidualNewtonOptions& o) const
{
  if (o.step_rtol <= 0)
    return false;
  PetscReal ndx, nx;
  PETSC_CHECK(VecNorm(_dx.get(), NORM_2, &ndx));
  PETSC_CHECK(VecNorm(_x.get(), NORM_2, &nx));
  return step * ndx <= o.step_rtol * nx && r <= o.accept_rtol * scale;
}

ResidualNewtonResult ResidualNewton::solve(double scale, const ResidualNewtonOptions& o,
                                           const std::function<void(int, double)>& progress)
{
  ResidualNewtonResult res;
  double r = residual_norm();
  for (int it = 0; it < o.max_iterations && r > o.rtol * scale; ++it)
  {
    assemble_jacobian();
    if (!solve_direction())
    {
      res.lu_failed = true;
      break;
    }
    double step;
    r = damped_step(r, o.max_halvings, step);
    res.iterations = it + 1;
    if (progress)
      progress(res.iterations, r);
    if (!std::isfinite(r) || stagnated(step, r, scale, o))
      break;
  }
  res.residual = r;
  return res;
}
} // namespace breastsim
