// SPDX-License-Identifier: LGPL-3.0-or-later
#include "block_csr_adder.hpp"
#include <algorithm>
#include <stdexcept>

namespace breastsim
{
namespace
{
PetscObject object(Mat A) { return reinterpret_cast<PetscObject>(A); }

/// block(a, b) += v(a, b) for a, b < bs: the block's rows are `stride`
/// apart in the CSR values, the element matrix's rows `ncols` apart.
inline void add_block(PetscScalar* block, PetscInt stride, const PetscScalar* v, std::size_t ncols,
                      std::size_t bs)
{
  for (std::size_t a = 0; a < bs; ++a)
    for (std::size_t b = 0; b < bs; ++b)
      block[a * stride + b] += v[a * ncols + b];
}
} // namespace

/// The CSR structure (row starts ia, columns ja) of one SeqAIJ part, given
/// back to PETSc by restore() or, when an exception unwinds, the destructor.
struct BlockCsrAdder::RowIJ
{
  Mat part = nullptr;
  PetscInt n = 0;
  const PetscInt *ia = nullptr, *ja = nullptr;
  PetscBool done = PETSC_FALSE;

  RowIJ() = default;
  RowIJ(const RowIJ&) = delete;
  RowIJ& operator=(const RowIJ&) = delete;
  ~RowIJ()
  {
    if (part) // unwinding: a destructor cannot throw
      MatRestoreRowIJ(part, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done);
  }
  void get(Mat m)
  {
    PETSC_CHECK(MatGetRowIJ(m, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
    part = m;
  }
  void restore()
  {
    if (Mat m = std::exchange(part, nullptr))
      PETSC_CHECK(MatRestoreRowIJ(m, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
  }
};

bool BlockCsrAdder::matches(Mat A) const
{
  PetscInt64 id;
  PETSC_CHECK(PetscObjectGetId(object(A), &id));
  PetscObjectState state;
  PETSC_CHECK(MatGetNonzeroState(A, &state));
  return id == _id && state == _nonzero_state;
}

BlockCsrAdder::Parts BlockCsrAdder::parts_of(Mat A)
{
  Parts parts;
  PetscBool seq, mpi;
  PETSC_CHECK(PetscObjectTypeCompare(object(A), MATSEQAIJ, &seq));
  PETSC_CHECK(PetscObjectTypeCompare(object(A), MATMPIAIJ, &mpi));
  parts.aij = seq || mpi;
  parts.count = mpi ? 2 : 1;
  parts.part[0] = A;
  if (mpi)
    PETSC_CHECK(MatMPIAIJGetSeqAIJ(A, &parts.part[0], &parts.part[1], &parts.garray));
  return parts;
}

void BlockCsrAdder::record(Mat A)
{
  _id = -1;
  const Parts parts = parts_of(A);
  if (!parts.aij)
    return;
  std::vector<PetscInt> off_block;
  if (parts.count == 2 && !off_diagonal_blocks(A, parts, off_block))
    return;
  if (!record_slots(parts, off_block))
    return;
  PETSC_CHECK(PetscObjectGetId(object(A), &_id));
  PETSC_CHECK(MatGetNonzeroState(A, &_nonzero_state));
}

bool BlockCsrAdder::off_diagonal_blocks(Mat A, const Parts& parts, std::vector<PetscInt>& block) const
{
  // Off-diagonal part: compressed column k holds global column garray[k];
  // its local block index comes from the matrix's (block) column mapping.
  const PetscInt bs = _bs;
  const PetscInt* garray = parts.garray;
  PetscInt m, n;
  PETSC_CHECK(MatGetSize(parts.part[1], &m, &n));
  ISLocalToGlobalMapping rmap, cmap;
  PETSC_CHECK(MatGetLocalToGlobalMapping(A, &rmap, &cmap));
  PetscInt map_bs = 0;
  if (cmap)
    PETSC_CHECK(ISLocalToGlobalMappingGetBlockSize(cmap, &map_bs));
  if (n % bs != 0 || map_bs != bs)
    return false;
  std::vector<PetscInt> global(n / bs);
  for (PetscInt k = 0; k < n / bs; ++k)
  {
    for (PetscInt b = 0; b < bs; ++b)
      if (garray[bs * k + b] != garray[bs * k] + b)
        return false;
    if (garray[bs * k] % bs != 0)
      return false;
    global[k] = garray[bs * k] / bs;
  }
  // -1 for columns this rank has no local index for: couplings that only
  // other ranks' cells (through this rank's rows they ghost) contribute.
  block.resize(global.size());
  PetscInt found = 0;
  PETSC_CHECK(ISGlobalToLocalMappingApplyBlock(cmap, IS_GTOLM_MASK, static_cast<PetscInt>(global.size()),
                                               global.data(), &found, block.data()));
  return true;
}

bool BlockCsrAdder::record_slots(const Parts& parts, const std::vector<PetscInt>& off_block)
{
  const PetscInt bs = _bs;
  const int nparts = parts.count;
  RowIJ ij[2];
  bool blocked = true;
  for (int p = 0; p < nparts; ++p)
  {
    ij[p].get(parts.part[p]);
    blocked = blocked && ij[p].done && ij[p].n == ij[0].n;
  }
  blocked = blocked && ij[0].n % bs == 0;
  _owned_rows = blocked ? ij[0].n / bs : 0;
  _row_slots.assign(_owned_rows + 1, 0);
  _slots.clear();
  _key = nullptr; // recorded offsets belong to the pattern recorded last
  for (int p = 0; p < 2; ++p)
    _stride[p].assign(p < nparts ? _owned_rows : 0, 0);
  for (PetscInt i = 0; i < _owned_rows && blocked; ++i)
    blocked = record_block_row(i, ij, nparts, off_block);
  // Offsets carry the part in their top bit: replay needs fewer than 2^31
  // values per part.
  _replayable = true;
  for (int p = 0; p < nparts && blocked; ++p)
    _replayable = _replayable && static_cast<std::int64_t>(ij[p].ia[ij[p].n]) < (std::int64_t(1) << 31);
  for (int p = 0; p < nparts; ++p)
    ij[p].restore();
  return blocked;
}

bool BlockCsrAdder::record_block_row(PetscInt i, const RowIJ* ij, int nparts,
                                     const std::vector<PetscInt>& off_block)
{
  // Blocked pattern: the bs rows of a block row share their columns, which
  // come in complete aligned groups of bs.
  const PetscInt bs = _bs, r0 = bs * i;
  const std::size_t first = _slots.size();
  bool blocked = true;
  for (int p = 0; p < nparts && blocked; ++p)
  {
    const PetscInt* ia = ij[p].ia;
    const PetscInt* row = ij[p].ja + ia[r0];
    const PetscInt len = ia[r0 + 1] - ia[r0];
    blocked = len % bs == 0;
    _stride[p][i] = len;
    for (PetscInt a = 1; a < bs && blocked; ++a)
      blocked = ia[r0 + a + 1] - ia[r0 + a] == len && std::equal(row, row + len, ij[p].ja + ia[r0 + a]);
    for (PetscInt k = 0; k < len && blocked; k += bs)
    {
      const PetscInt c = row[k];
      blocked = c % bs == 0;
      for (PetscInt b = 1; b < bs && blocked; ++b)
        blocked = row[k + b] == c + b;
      const PetscInt col = p == 0 ? c / bs : off_block[c / bs];
      if (col >= 0)
        _slots.push_back({static_cast<std::int32_t>(col), p, ia[r0] + k});
    }
  }
  std::sort(_slots.begin() + first, _slots.end(),
            [](const Slot& x, const Slot& y) { return x.col < y.col; });
  _row_slots[i + 1] = static_cast<PetscInt>(_slots.size());
  return blocked;
}

void BlockCsrAdder::begin(Mat A, const void* key)
{
  _A = A;
  _parts[0] = A;
  _parts[1] = nullptr;
  try
  {
    PetscBool mpi;
    PETSC_CHECK(PetscObjectTypeCompare(object(A), MATMPIAIJ, &mpi));
    if (mpi)
      PETSC_CHECK(MatMPIAIJGetSeqAIJ(A, &_parts[0], &_parts[1], nullptr));
    for (int p = 0; p < 2; ++p)
      if (_parts[p])
        PETSC_CHECK(MatSeqAIJGetArray(_parts[p], &_values[p]));
  }
  catch (...)
  {
    cancel(A);
    throw;
  }
  _current = key;
  _call = _position = 0;
  _last_replayed = false;
  if (key && key == _key)
    _mode = Mode::replay;
  else if (key && _replayable)
  {
    _mode = Mode::record;
    _key = nullptr;
    _indices.clear();
    _call_start.assign(1, 0);
    _offsets.clear();
  }
  else
    _mode = Mode::search;
}

void BlockCsrAdder::restore_arrays()
{
  for (int p = 0; p < 2; ++p)
    if (PetscScalar* values = std::exchange(_values[p], nullptr))
      PETSC_CHECK(MatSeqAIJRestoreArray(_parts[p], &values));
  _parts[0] = _parts[1] = nullptr;
  _A = nullptr;
}

void BlockCsrAdder::end(Mat)
{
  restore_arrays();
  if (_mode == Mode::record)
    _key = _current; // complete: the next assembly with this key replays
  else if (_mode == Mode::replay)
  {
    _last_replayed = _call + 1 == _call_start.size();
    if (!_last_replayed)
      _key = nullptr; // fewer calls than recorded: record afresh next time
  }
  _mode = Mode::search;
}

void BlockCsrAdder::cancel(Mat) noexcept
{
  for (int p = 0; p < 2; ++p)
    if (_values[p]) // cleanup while an exception unwinds: errors cannot be reported
      MatSeqAIJRestoreArray(_parts[p], &_values[p]);
  _values[0] = _values[1] = nullptr;
  _parts[0] = _parts[1] = nullptr;
  _A = nullptr;
  _key = nullptr; // an incomplete recording or replay: record afresh next time
  _mode = Mode::search;
  _last_replayed = false;
}

const BlockCsrAdder::Slot& BlockCsrAdder::locate(std::int32_t row, std::int32_t col) const
{
  const auto first = _slots.begin() + _row_slots[row];
  const auto last = _slots.begin() + _row_slots[row + 1];
  const auto it = std::lower_bound(first, last, col,
                                   [](const Slot& s, std::int32_t c) { return s.col < c; });
  if (it == last || it->col != col)
    throw std::runtime_error("BlockCsrAdder: entry outside the recorded matrix pattern");
  return *it;
}

void BlockCsrAdder::add_ghost_row(PetscInt row, std::span<const std::int32_t> cols,
                                  const PetscScalar* row_values)
{
  // A ghost node's row: PETSc sends it to its owner at assembly.
  _petsc_cols.assign(cols.begin(), cols.end());
  PETSC_CHECK(MatSetValuesBlockedLocal(_A, 1, &row, static_cast<PetscInt>(_petsc_cols.size()),
                                       _petsc_cols.data(), row_values, ADD_VALUES));
}

bool BlockCsrAdder::is_next_recorded_call(std::span<const std::int32_t> rows,
                                          std::span<const std::int32_t> cols) const
{
  return _call + 1 < _call_start.size()
         && _call_start[_call + 1] - _call_start[_call] == rows.size() + cols.size()
         && std::equal(rows.begin(), rows.end(), _indices.begin() + _call_start[_call])
         && std::equal(cols.begin(), cols.end(), _indices.begin() + _call_start[_call] + rows.size());
}

inline std::pair<std::int32_t, PetscInt> BlockCsrAdder::block_offset(std::int32_t r, std::int32_t col)
{
  if (_mode == Mode::replay)
  {
    // The part in the top bit, the offset below it.
    const std::uint32_t e = _offsets[_position++];
    return {static_cast<std::int32_t>(e >> 31), static_cast<PetscInt>(e & 0x7fffffffu)};
  }
  const Slot& slot = locate(r, col);
  if (_mode == Mode::record)
    _offsets.push_back(static_cast<std::uint32_t>(slot.offset)
                       | (static_cast<std::uint32_t>(slot.part) << 31));
  return {slot.part, slot.offset};
}

void BlockCsrAdder::add(std::span<const std::int32_t> rows, std::span<const std::int32_t> cols,
                        std::span<const PetscScalar> values)
{
  if (_mode == Mode::replay)
  {
    // The call must be the recorded one, rows and columns alike.
    if (!is_next_recorded_call(rows, cols))
    {
      _mode = Mode::search;
      _key = nullptr;
    }
    ++_call;
  }
  else if (_mode == Mode::record)
  {
    _indices.insert(_indices.end(), rows.begin(), rows.end());
    _indices.insert(_indices.end(), cols.begin(), cols.end());
    _call_start.push_back(_indices.size());
  }
  const std::size_t bs = _bs, ncols = cols.size() * bs;
  for (std::size_t i = 0; i < rows.size(); ++i)
  {
    const std::int32_t r = rows[i];
    const PetscScalar* row_values = values.data() + i * bs * ncols;
    if (r >= _owned_rows)
    {
      add_ghost_row(r, cols, row_values);
      continue;
    }
    const PetscInt stride[2] = {_stride[0][r], _stride[1].empty() ? 0 : _stride[1][r]};
    for (std::size_t j = 0; j < cols.size(); ++j)
    {
      const auto [part, offset] = block_offset(r, cols[j]);
      add_block(_values[part] + offset, stride[part], row_values + j * bs, ncols, bs);
    }
  }
}
} // namespace breastsim
