#pragma once
// Assemble a linear form into a ghosted PETSc vector from zero:
//   b = 0 (owned and ghost entries), b += L, ghost contributions summed
//   into their owners (reverse scatter).
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/petsc.h>
#include <petscvec.h>

namespace breastsim
{
inline void assemble_ghosted(Vec b, const dolfinx::fem::Form<PetscScalar>& L)
{
  Vec local;
  VecGhostGetLocalForm(b, &local);
  VecSet(local, 0.0);
  VecGhostRestoreLocalForm(b, &local);
  dolfinx::fem::petsc::assemble_vector(b, L);
  VecGhostUpdateBegin(b, ADD_VALUES, SCATTER_REVERSE);
  VecGhostUpdateEnd(b, ADD_VALUES, SCATTER_REVERSE);
}
} // namespace breastsim
