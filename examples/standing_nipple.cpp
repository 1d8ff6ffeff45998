// SPDX-License-Identifier: LGPL-3.0-or-later
// A program built against the installed breastsim package: mesh the default
// half breast, solve it standing, print where the nipple went.
//   cmake -S examples -B build-example -DCMAKE_PREFIX_PATH=<install prefix>
//   cmake --build build-example && build-example/standing_nipple
#include "case_options.hpp"
#include "model_setup.hpp"
#include "neutral_mesh.hpp"
#include "newton.hpp"
#include "posture_solve.hpp"
#include "solver_options.hpp"
#include <cstdio>
#include <dolfinx/common/log.h>
#include <petscsys.h>

int main()
{
  using namespace breastsim;
  if (PetscInitializeNoArguments() != 0)
    return 1;
  loguru::g_stderr_verbosity = loguru::Verbosity_WARNING; // dolfinx's own log: warnings only
  {
    Config c; // every key at its default (`breastsim keys`)
    c.set("geometry.mesh_size", 0.012);
    c.validate();
    Model model(build_neutral_mesh(c, MPI_COMM_WORLD), Constraints{true, c.flag("base.fixed")});
    apply_parameters(c, model);
    NewtonSolver newton(model, NewtonOptions::from(c));
    const ObservableProbe probe(model, CaseOptions::from(c).geometry.nipple());
    const PostureResult r = solve_posture(model, newton, probe, named_posture("standing"), c);
    const auto& x = r.observables.nipple;
    std::printf("standing nipple [mm]: %.2f %.2f %.2f\n", 1e3 * x[0], 1e3 * x[1], 1e3 * x[2]);
  }
  return PetscFinalize() == 0 ? 0 : 1;
}
