// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Assemble a linear form into a ghosted PETSc vector from zero:
//   b = 0 (owned and ghost entries), b += L, ghost contributions summed
//   into their owners (reverse scatter).
#include "petsc.hpp"
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/petsc.h>
#include <petscvec.h>

namespace breastsim
{
/// The local form (owned and ghost entries) of a ghosted vector, borrowed
/// until restore() or, when an exception unwinds, the destructor.
class GhostLocalForm
{
public:
  explicit GhostLocalForm(Vec b) : _b(b) { PETSC_CHECK(VecGhostGetLocalForm(_b, &_local)); }
  ~GhostLocalForm()
  {
    if (_local)
      VecGhostRestoreLocalForm(_b, &_local); // unwinding: a destructor cannot throw
  }
  GhostLocalForm(const GhostLocalForm&) = delete;
  GhostLocalForm& operator=(const GhostLocalForm&) = delete;
  Vec get() const { return _local; }
  void restore()
  {
    Vec local = std::exchange(_local, nullptr);
    PETSC_CHECK(VecGhostRestoreLocalForm(_b, &local));
  }

private:
  Vec _b;
  Vec _local = nullptr;
};

inline void assemble_ghosted(Vec b, const dolfinx::fem::Form<PetscScalar>& L)
{
  GhostLocalForm local(b);
  PETSC_CHECK(VecSet(local.get(), 0.0));
  local.restore();
  dolfinx::fem::petsc::assemble_vector(b, L);
  PETSC_CHECK(VecGhostUpdateBegin(b, ADD_VALUES, SCATTER_REVERSE));
  PETSC_CHECK(VecGhostUpdateEnd(b, ADD_VALUES, SCATTER_REVERSE));
}
} // namespace breastsim
