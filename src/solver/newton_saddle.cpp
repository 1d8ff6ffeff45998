// SPDX-License-Identifier: LGPL-3.0-or-later
// NewtonSolver's line search for a saddle point (the mixed (u, p)
// formulation): the Lagrangian Pi(u, p) is concave in p, so neither an
// energy decrease nor r . du < 0 characterises progress. Backtracking on the
// residual norm instead, never accepting an inverted element:
//   accept the first a = 1, 1/2, ... with det F > 0 and |r(w + a dw)| <= (1 - 1e-4 a) |r(w)|.
#include "newton.hpp"
#include <cmath>

namespace breastsim
{
double NewtonSolver::residual_line_search(Vec u, double rnorm, double& energy)
{
  PETSC_CHECK(VecCopy(u, _u0.get()));
  double step = 2.0;
  for (int k = 0; k <= _opt.max_backtracks; ++k)
  {
    step *= 0.5;
    PETSC_CHECK(VecWAXPY(u, step, _du.get(), _u0.get()));
    _model.set_displacement(u);
    if (!(_model.min_detF() > 0))
      continue;
    const double r = residual_norm();
    if (std::isfinite(r) && r <= (1 - 1e-4 * step) * rnorm)
    {
      energy = _model.energy();
      return step;
    }
  }
  PETSC_CHECK(VecCopy(_u0.get(), u));
  _model.set_displacement(u);
  return 0;
}
} // namespace breastsim
