// SPDX-License-Identifier: LGPL-3.0-or-later
// NewtonSolver's line search for a saddle point (the mixed (u, p)
// formulation): the Lagrangian Pi(u, p) is concave in p, so neither an
// energy decrease nor r . du < 0 characterises progress. Backtracking on the
// residual norm instead (NewtonSolver::backtrack, which never accepts an
// inverted element):  |r(w + a dw)| <= (1 - 1e-4 a) |r(w)|.
#include "newton.hpp"
#include <cmath>

namespace breastsim
{
double NewtonSolver::residual_line_search(Vec u, double rnorm, double& energy)
{
  return backtrack(u, [&](double step)
  {
    const double r = residual_norm();
    if (!(std::isfinite(r) && r <= (1 - 1e-4 * step) * rnorm))
      return false;
    energy = _model.energy();
    return true;
  });
}
} // namespace breastsim
