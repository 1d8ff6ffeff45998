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
  _key = nullptr; // recorded offsets belong to the old pattern
  for (int p = 0; p < 2; ++p)
    _stride[p].assign(p < nparts ? _owned_rows : 0, 0);
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
      _stride[p][i] = len;
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
          _slots.push_back({static_cast<std::int32_t>(col), p, ia[p][r0] + k});
      }
    }
    std::sort(_slots.begin() + first, _slots.end(),
              [](const Slot& x, const Slot& y) { return x.col < y.col; });
    _row_slots[i + 1] = static_cast<PetscInt>(_slots.size());
  }
  // Offsets carry the part in their top bit: replay needs fewer than 2^31
  // values per part.
  _replayable = true;
  for (int p = 0; p < nparts && blocked; ++p)
    _replayable = _replayable && static_cast<std::int64_t>(ia[p][n[p]]) < (std::int64_t(1) << 31);
  for (int p = 0; p < nparts; ++p)
    MatRestoreRowIJ(parts[p], 0, PETSC_FALSE, PETSC_FALSE, &n[p], &ia[p], &ja[p], &done[p]);
  if (!blocked)
    return;
  PetscObjectGetId(reinterpret_cast<PetscObject>(A), &_id);
  MatGetNonzeroState(A, &_nonzero_state);
}

void BlockCsrAdder::begin(Mat A, const void* key)
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

void BlockCsrAdder::end(Mat)
{
  for (int p = 0; p < 2; ++p)
    if (_parts[p])
      MatSeqAIJRestoreArray(_parts[p], &_values[p]);
  _values[0] = _values[1] = nullptr;
  _parts[0] = _parts[1] = nullptr;
  _A = nullptr;
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
  MatSetValuesBlockedLocal(_A, 1, &row, static_cast<PetscInt>(_petsc_cols.size()),
                           _petsc_cols.data(), row_values, ADD_VALUES);
}

void BlockCsrAdder::add(std::span<const std::int32_t> rows, std::span<const std::int32_t> cols,
                        std::span<const PetscScalar> values)
{
  if (_mode == Mode::replay)
  {
    // The call must be the recorded one, rows and columns alike.
    const bool same = _call + 1 < _call_start.size()
                      && _call_start[_call + 1] - _call_start[_call] == rows.size() + cols.size()
                      && std::equal(rows.begin(), rows.end(), _indices.begin() + _call_start[_call])
                      && std::equal(cols.begin(), cols.end(),
                                    _indices.begin() + _call_start[_call] + rows.size());
    if (!same)
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
    if (r >= _owned_rows)
    {
      add_ghost_row(r, cols, values.data() + i * bs * ncols);
      continue;
    }
    const PetscInt stride[2] = {_stride[0][r], _stride[1].empty() ? 0 : _stride[1][r]};
    for (std::size_t j = 0; j < cols.size(); ++j)
    {
      // Block A(r, c): its offset from the replay, else searched (and
      // recorded, the part in the top bit).
      std::int32_t part;
      PetscInt offset;
      if (_mode == Mode::replay)
      {
        const std::uint32_t e = _offsets[_position++];
        part = static_cast<std::int32_t>(e >> 31);
        offset = e & 0x7fffffffu;
      }
      else
      {
        const Slot& slot = locate(r, cols[j]);
        part = slot.part;
        offset = slot.offset;
        if (_mode == Mode::record)
          _offsets.push_back(static_cast<std::uint32_t>(offset)
                             | (static_cast<std::uint32_t>(part) << 31));
      }
      PetscScalar* block = _values[part] + offset;
      const PetscInt s = stride[part];
      const PetscScalar* v = values.data() + i * bs * ncols + j * bs;
      for (std::size_t a = 0; a < bs; ++a)
        for (std::size_t b = 0; b < bs; ++b)
          block[a * s + b] += v[a * ncols + b];
    }
  }
}
} // namespace breastsim
