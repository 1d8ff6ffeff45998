// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The state of the mixed (u, p) formulation (tissue.formulation = mixed,
// forms/mixed_forms_common.py): Taylor-Hood w = (u, p) in W = V_u x Q. The
// model keeps the displacement u in the collapsed space V_u (what the
// observables, writers and solvers read as the displacement) and w as the
// Newton unknown; u is the master copy of the displacement part:
//   pull: w|_u = u  (before every assembly),   push: u = w|_u  (after a Newton update).
#include "case_options.hpp"
#include "mesh_from_gmsh.hpp"
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <memory>
#include <petscsystypes.h>
#include <vector>

namespace breastsim
{
class MixedState
{
public:
  using T = PetscScalar;
  /// W on the mesh (needs element degree 2: InputError naming
  /// tissue.formulation otherwise), w = 0, the collapsed displacement space.
  explicit MixedState(const TaggedDolfinxMesh& mesh);

  std::shared_ptr<dolfinx::fem::FunctionSpace> W() const { return _W; }
  std::shared_ptr<dolfinx::fem::FunctionSpace> displacement_space() const { return _V; }
  std::shared_ptr<dolfinx::fem::Function<T>> w() const { return _w; }
  /// w's displacement part = u (ghosts updated).
  void pull(const dolfinx::fem::Function<T>& u);
  /// u = w's displacement part (ghosts updated).
  void push(dolfinx::fem::Function<T>& u) const;
  /// The constraints on W: u_x = 0 on the symmetry face, u = 0 on the base if fixed.
  std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<T>>>
  bcs(const TaggedDolfinxMesh& mesh, bool symmetry, bool fixed_base) const;
  /// Global number of unknowns of w.
  std::int64_t num_dofs() const;

private:
  std::shared_ptr<dolfinx::fem::FunctionSpace> _W, _V;
  std::shared_ptr<dolfinx::fem::Function<T>> _w;
  std::vector<std::int32_t> _map; ///< dof of V_u (unrolled) -> dof of W
};

/// "displacement" or "mixed".
std::string to_string(TissueFormulation f);
} // namespace breastsim
