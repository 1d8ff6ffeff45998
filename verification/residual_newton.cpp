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
  _A = fem::petsc::create_matrix(*_J, "aij");
  _b = la::petsc::create_vector(*V->dofmap()->index_map, V->dofmap()->index_map_bs());
  VecDuplicate(_b, &_dx);
  _x = la::petsc::create_vector_wrap(*_u->x());
  KSPCreate(V->mesh()->comm(), &_ksp);
  KSPSetType(_ksp, KSPPREONLY);
  PC pc;
  KSPGetPC(_ksp, &pc);
  PCSetType(pc, PCLU);
  PCFactorSetMatSolverType(pc, MATSOLVERMUMPS);
}

ResidualNewton::~ResidualNewton()
{
  KSPDestroy(&_ksp);
  VecDestroy(&_x);
  VecDestroy(&_dx);
  VecDestroy(&_b);
  MatDestroy(&_A);
}

double ResidualNewton::residual_norm()
{
  assemble_ghosted(_b, *_R);
  fem::petsc::set_bc(_b, _bcs, _x, -1.0);
  PetscReal n;
  VecNorm(_b, NORM_2, &n);
  return double(n);
}

ResidualNewtonResult ResidualNewton::solve(double scale, const ResidualNewtonOptions& o,
                                           const std::function<void(int, double)>& progress)
{
  ResidualNewtonResult res;
  double r = residual_norm();
  auto V = _u->function_space();
  for (int it = 0; it < o.max_iterations && r > o.rtol * scale; ++it)
  {
    MatZeroEntries(_A);
    fem::assemble_matrix(la::petsc::Matrix::set_block_fn(_A, ADD_VALUES), *_J, _bcs);
    MatAssemblyBegin(_A, MAT_FLUSH_ASSEMBLY);
    MatAssemblyEnd(_A, MAT_FLUSH_ASSEMBLY);
    fem::set_diagonal<T>(la::petsc::Matrix::set_fn(_A, INSERT_VALUES), *V, _bcs);
    MatAssemblyBegin(_A, MAT_FINAL_ASSEMBLY);
    MatAssemblyEnd(_A, MAT_FINAL_ASSEMBLY);
    KSPSetOperators(_ksp, _A, _A);
    KSPSolve(_ksp, _b, _dx);
    KSPConvergedReason reason;
    KSPGetConvergedReason(_ksp, &reason);
    if (reason < 0)
    {
      res.lu_failed = true;
      break;
    }
    // Full step, halved while the residual norm grows or is not finite
    // (ln J of an inverted trial state).
    const double r_old = r;
    double step = 1.0;
    VecAXPY(_x, -step, _dx);
    _u->x()->scatter_fwd();
    r = residual_norm();
    for (int k = 0; k < o.max_halvings && !(r < r_old); ++k)
    {
      step *= 0.5;
      VecAXPY(_x, step, _dx); // back to half of the previous step
      _u->x()->scatter_fwd();
      r = residual_norm();
    }
    res.iterations = it + 1;
    if (progress)
      progress(res.iterations, r);
    if (!std::isfinite(r))
      break;
    if (o.step_rtol > 0)
    {
      PetscReal ndx, nx;
      VecNorm(_dx, NORM_2, &ndx);
      VecNorm(_x, NORM_2, &nx);
      if (step * ndx <= o.step_rtol * nx && r <= o.accept_rtol * scale)
        break;
    }
  }
  res.residual = r;
  return res;
}
} // namespace breastsim
