#include "block_csr_adder.hpp"
#include <algorithm>
#include <stdexcept>

namespace breastsim
{
bool BlockCsrAdder::matches(Mat A) const
{
  PetscInt64 id;
  PetscObjectGetId(reinterpret_cast<PetscObject>(A), &id);
  PetscObjectState state;
  MatGetNonzeroState(A, &state);
  return id == _id && state == _nonzero_state;
}

void BlockCsrAdder::record(Mat A)
{
  _id = -1;
  PetscBool seq, mpi;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATSEQAIJ, &seq);
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATMPIAIJ, &mpi);
  if (!seq && !mpi)
    return;
  const PetscInt bs = _bs;
  Mat parts[2] = {A, nullptr};
  const PetscInt* garray = nullptr;
  if (mpi)
    MatMPIAIJGetSeqAIJ(A, &parts[0], &parts[1], &garray);
  const int nparts = mpi ? 2 : 1;

  // Off-diagonal part: compressed column k holds global column garray[k];
  // its local block index comes from the matrix's (block) column mapping.
  std::vector<PetscInt> off_block;
  if (mpi)
  {
    PetscInt m, n;
    MatGetSize(parts[1], &m, &n);
    ISLocalToGlobalMapping rmap, cmap;
    MatGetLocalToGlobalMapping(A, &rmap, &cmap);
    PetscInt map_bs = 0;
    if (cmap)
      ISLocalToGlobalMappingGetBlockSize(cmap, &map_bs);
    if (n % bs != 0 || map_bs != bs)
      return;
    std::vector<PetscInt> global(n / bs);
    for (PetscInt k = 0; k < n / bs; ++k)
    {
      for (PetscInt b = 0; b < bs; ++b)
        if (garray[bs * k + b] != garray[bs * k] + b)
          return;
      if (garray[bs * k] % bs != 0)
        return;
      global[k] = garray[bs * k] / bs;
    }
    // -1 for columns this rank has no local index for: couplings that only
    // other ranks' cells (through this rank's rows they ghost) contribute.
    off_block.resize(global.size());
    PetscInt found = 0;
    ISGlobalToLocalMappingApplyBlock(cmap, IS_GTOLM_MASK, static_cast<PetscInt>(global.size()),
                                     global.data(), &found, off_block.data());
  }

  PetscInt n[2] = {0, 0};
  const PetscInt *ia[2] = {nullptr, nullptr}, *ja[2] = {nullptr, nullptr};
  PetscBool done[2] = {PETSC_FALSE, PETSC_FALSE};
  bool blocked = true;
  for (int p = 0; p < nparts; ++p)
  {
    MatGetRowIJ(parts[p], 0, PETSC_FALSE, PETSC_FALSE, &n[p], &ia[p], &ja[p], &done[p]);
    blocked = blocked && done[p] && n[p] == n[0];
  }
  blocked = blocked && n[0] % bs == 0;
  _owned_rows = blocked ? n[0] / bs : 0;
  _row_slots.assign(_owned_rows + 1, 0);
  _slots.clear();
  // Blocked pattern: the bs rows of a block row share their columns, which
  // come in complete aligned groups of bs.
  for (PetscInt i = 0; i < _owned_rows && blocked; ++i)
  {
    const PetscInt r0 = bs * i;
    const std::size_t first = _slots.size();
    for (int p = 0; p < nparts && blocked; ++p)
    {
      const PetscInt* row = ja[p] + ia[p][r0];
      const PetscInt len = ia[p][r0 + 1] - ia[p][r0];
      blocked = len % bs == 0;
      for (PetscInt a = 1; a < bs && blocked; ++a)
        blocked = ia[p][r0 + a + 1] - ia[p][r0 + a] == len && std::equal(row, row + len, ja[p] + ia[p][r0 + a]);
      for (PetscInt k = 0; k < len && blocked; k += bs)
      {
        const PetscInt c = row[k];
        blocked = c % bs == 0;
        for (PetscInt b = 1; b < bs && blocked; ++b)
          blocked = row[k + b] == c + b;
        const PetscInt col = p == 0 ? c / bs : off_block[c / bs];
        if (col >= 0)
          _slots.push_back({static_cast<std::int32_t>(col), p, ia[p][r0] + k, len});
      }
    }
    std::sort(_slots.begin() + first, _slots.end(),
              [](const Slot& x, const Slot& y) { return x.col < y.col; });
    _row_slots[i + 1] = static_cast<PetscInt>(_slots.size());
  }
  for (int p = 0; p < nparts; ++p)
    MatRestoreRowIJ(parts[p], 0, PETSC_FALSE, PETSC_FALSE, &n[p], &ia[p], &ja[p], &done[p]);
  if (!blocked)
    return;
  PetscObjectGetId(reinterpret_cast<PetscObject>(A), &_id);
  MatGetNonzeroState(A, &_nonzero_state);
}

void BlockCsrAdder::begin(Mat A)
{
  _A = A;
  _parts[0] = A;
  _parts[1] = nullptr;
  PetscBool mpi;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATMPIAIJ, &mpi);
  if (mpi)
    MatMPIAIJGetSeqAIJ(A, &_parts[0], &_parts[1], nullptr);
  for (int p = 0; p < 2; ++p)
    if (_parts[p])
      MatSeqAIJGetArray(_parts[p], &_values[p]);
}

void BlockCsrAdder::end(Mat)
{
  for (int p = 0; p < 2; ++p)
    if (_parts[p])
      MatSeqAIJRestoreArray(_parts[p], &_values[p]);
  _values[0] = _values[1] = nullptr;
  _parts[0] = _parts[1] = nullptr;
  _A = nullptr;
}

void BlockCsrAdder::add(std::span<const std::int32_t> rows, std::span<const std::int32_t> cols,
                        std::span<const PetscScalar> values)
{
  const std::size_t bs = _bs, ncols = cols.size() * bs;
  for (std::size_t i = 0; i < rows.size(); ++i)
  {
    const std::int32_t r = rows[i];
    if (r >= _owned_rows)
    {
      // A ghost node's row: PETSc sends it to its owner at assembly.
      const PetscInt row = r;
      _petsc_cols.assign(cols.begin(), cols.end());
      MatSetValuesBlockedLocal(_A, 1, &row, static_cast<PetscInt>(_petsc_cols.size()), _petsc_cols.data(),
                               values.data() + i * bs * ncols, ADD_VALUES);
      continue;
    }
    const auto first = _slots.begin() + _row_slots[r];
    const auto last = _slots.begin() + _row_slots[r + 1];
    for (std::size_t j = 0; j < cols.size(); ++j)
    {
      const auto it = std::lower_bound(first, last, cols[j],
                                       [](const Slot& s, std::int32_t c) { return s.col < c; });
      if (it == last || it->col != cols[j])
        throw std::runtime_error("BlockCsrAdder: entry outside the recorded matrix pattern");
      PetscScalar* block = _values[it->part] + it->offset;
      const PetscInt stride = it->stride;
      const PetscScalar* v = values.data() + i * bs * ncols + j * bs;
      for (std::size_t a = 0; a < bs; ++a)
        for (std::size_t b = 0; b < bs; ++b)
          block[a * stride + b] += v[a * ncols + b];
    }
  }
}
} // namespace breastsim
