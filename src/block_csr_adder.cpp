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
  PetscBool seqaij;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATSEQAIJ, &seqaij);
  if (!seqaij)
    return;
  PetscInt n;
  const PetscInt *ia, *ja;
  PetscBool done;
  MatGetRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done);
  if (!done)
    return;
  const PetscInt bs = _bs;
  bool blocked = n % bs == 0;
  const PetscInt nb = blocked ? n / bs : 0;
  _row_start.assign(nb, 0);
  _row_length.assign(nb, 0);
  _block_start.assign(nb + 1, 0);
  _block_cols.clear();
  // Blocked pattern: the bs rows of a block row share their columns, which
  // come in complete aligned groups of bs.
  for (PetscInt i = 0; i < nb && blocked; ++i)
  {
    const PetscInt r0 = bs * i, len = ia[r0 + 1] - ia[r0];
    blocked = len % bs == 0;
    for (PetscInt a = 1; a < bs && blocked; ++a)
      blocked = ia[r0 + a + 1] - ia[r0 + a] == len
                && std::equal(ja + ia[r0], ja + ia[r0 + 1], ja + ia[r0 + a]);
    for (PetscInt k = 0; k < len && blocked; k += bs)
    {
      const PetscInt c = ja[ia[r0] + k];
      blocked = c % bs == 0;
      for (PetscInt b = 1; b < bs && blocked; ++b)
        blocked = ja[ia[r0] + k + b] == c + b;
      _block_cols.push_back(static_cast<std::int32_t>(c / bs));
    }
    _row_start[i] = ia[r0];
    _row_length[i] = len;
    _block_start[i + 1] = static_cast<PetscInt>(_block_cols.size());
  }
  MatRestoreRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done);
  if (!blocked)
    return;
  PetscObjectGetId(reinterpret_cast<PetscObject>(A), &_id);
  MatGetNonzeroState(A, &_nonzero_state);
}

void BlockCsrAdder::begin(Mat A) { MatSeqAIJGetArray(A, &_values); }

void BlockCsrAdder::end(Mat A)
{
  MatSeqAIJRestoreArray(A, &_values);
  _values = nullptr;
}

void BlockCsrAdder::add(std::span<const std::int32_t> rows, std::span<const std::int32_t> cols,
                        std::span<const PetscScalar> values)
{
  const std::size_t bs = _bs, ncols = cols.size() * bs;
  for (std::size_t i = 0; i < rows.size(); ++i)
  {
    const std::int32_t r = rows[i];
    const auto first = _block_cols.begin() + _block_start[r];
    const auto last = _block_cols.begin() + _block_start[r + 1];
    const PetscInt len = _row_length[r];
    for (std::size_t j = 0; j < cols.size(); ++j)
    {
      const auto it = std::lower_bound(first, last, cols[j]);
      if (it == last || *it != cols[j])
        throw std::runtime_error("BlockCsrAdder: entry outside the recorded matrix pattern");
      PetscScalar* block = _values + _row_start[r] + bs * (it - first);
      const PetscScalar* v = values.data() + i * bs * ncols + j * bs;
      for (std::size_t a = 0; a < bs; ++a)
        for (std::size_t b = 0; b < bs; ++b)
          block[a * len + b] += v[a * ncols + b];
    }
  }
}
} // namespace breastsim
