// SPDX-License-Identifier: LGPL-3.0-or-later
// Model's matrix helpers: the Jacobian's pattern inserted into a new
// matrix, partner couplings added to it.
#include "model.hpp"
#include "petsc.hpp"
#include <algorithm>
#include <dolfinx/common/IndexMap.h>

namespace breastsim
{
using namespace dolfinx;

void Model::add_scaled(Mat A, Mat K, double s) const
{
  // Entries outside the preallocation (a matrix created while the term was
  // off) are allocated.
  PETSC_CHECK(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  PetscInt r0, r1;
  PETSC_CHECK(MatGetOwnershipRange(K, &r0, &r1));
  std::vector<PetscInt> cols;
  std::vector<PetscScalar> vals;
  for (PetscInt r = r0; r < r1; ++r)
  {
    // Row r of K copied (and scaled) before it is given back to PETSc.
    PetscInt n;
    const PetscInt* c;
    const PetscScalar* v;
    PETSC_CHECK(MatGetRow(K, r, &n, &c, &v));
    cols.assign(c, c + n);
    vals.assign(v, v + n);
    PETSC_CHECK(MatRestoreRow(K, r, &n, &c, &v));
    for (auto& x : vals)
      x *= s;
    PETSC_CHECK(MatSetValues(A, 1, &r, static_cast<PetscInt>(cols.size()), cols.data(), vals.data(),
                             ADD_VALUES));
  }
}

void Model::insert_coupling_blocks(Mat A, Mat K)
{
  // Zero blocks of A at the blocks of K's nonzeros: block row r / 3 with the
  // blocks c / 3 of row r (global indices; rows owned by this rank, whose
  // columns may lie on any rank), allocated beyond A's preallocation.
  PETSC_CHECK(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  PetscInt r0, r1;
  PETSC_CHECK(MatGetOwnershipRange(K, &r0, &r1));
  std::vector<PetscInt> blocks;
  std::vector<PetscScalar> zeros;
  for (PetscInt r = r0; r < r1; ++r)
  {
    PetscInt n;
    const PetscInt* cols;
    PETSC_CHECK(MatGetRow(K, r, &n, &cols, nullptr));
    blocks.assign(cols, cols + n);
    PETSC_CHECK(MatRestoreRow(K, r, &n, &cols, nullptr));
    for (auto& c : blocks)
      c /= 3;
    std::sort(blocks.begin(), blocks.end());
    blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
    zeros.assign(9 * blocks.size(), 0.0);
    const PetscInt row = r / 3;
    PETSC_CHECK(MatSetValuesBlocked(A, 1, &row, static_cast<PetscInt>(blocks.size()), blocks.data(), zeros.data(),
                                    ADD_VALUES));
  }
}

void Model::insert_pattern(Mat A, const la::SparsityPattern& pattern) const
{
  // Zeros at every entry of the pattern, one block row at a time (global,
  // sorted columns: PETSc appends instead of searching), then the final
  // assembly that makes the CSR structure.
  const auto& graph = pattern.graph();
  const std::vector<std::int64_t> global_cols = pattern.column_index_map().global_indices();
  const std::int64_t row0 = pattern.index_map(0)->local_range()[0];
  const int bs = pattern.block_size(0);
  std::vector<PetscInt> cols;
  std::vector<PetscScalar> zeros;
  // Owned rows only: assemble() has sent the ghost rows' entries to their owners.
  const std::int32_t owned = pattern.index_map(0)->size_local();
  for (std::int32_t i = 0; i < owned; ++i)
  {
    auto links = graph.links(i);
    cols.resize(links.size());
    for (std::size_t k = 0; k < links.size(); ++k)
      cols[k] = static_cast<PetscInt>(global_cols[links[k]]);
    std::sort(cols.begin(), cols.end());
    zeros.assign(bs * bs * cols.size(), 0.0);
    const PetscInt row = static_cast<PetscInt>(row0 + i);
    PETSC_CHECK(MatSetValuesBlocked(A, 1, &row, static_cast<PetscInt>(cols.size()), cols.data(),
                                    zeros.data(), INSERT_VALUES));
  }
  PETSC_CHECK(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PETSC_CHECK(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
}

} // namespace breastsim
