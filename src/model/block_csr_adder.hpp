// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Fast addition of element matrices into an assembled PETSc AIJ matrix
// (serial SeqAIJ, or MPIAIJ: its diagonal and off-diagonal SeqAIJ parts)
// whose nonzero pattern is made of bs x bs blocks (vector P1/P2 spaces).
//
// PETSc's MatSetValuesBlockedLocal on AIJ expands every element matrix into
// scalar rows and binary-searches each of the (n bs)^2 columns, most of the
// Jacobian assembly's time (docs/PERFORMANCE.md, "Figures moved from code
// comments"). Here one search per block pair finds the block's offset in the
// CSR row, and the bs^2 values are added straight into the value array.
// Under MPI, rows owned by this rank go straight into the diagonal or
// off-diagonal part (columns located through the matrix's local-to-global
// mapping and the off-diagonal part's column map); rows of ghost nodes go
// through PETSc (MatSetValuesBlockedLocal, communicated at assembly).
//
// Replay: an assembly of the same form visits the same cells and facets in
// the same order, so the first assembly with a given key records, call by
// call, the element's rows and columns and each block's value offset; the
// next ones with that key compare each call's rows and columns with the
// recorded ones (exactly) and add through the recorded offsets, without
// searching. A call that differs ends the replay for that assembly (it and
// the rest are searched, and the next assembly records afresh), so a
// replayed assembly always writes where a searched one would.
#include "petsc.hpp"
#include <petscmat.h>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace breastsim
{
class BlockCsrAdder
{
public:
  explicit BlockCsrAdder(int bs) : _bs(bs) {}
  /// True when A is the matrix whose pattern was recorded by the last
  /// record() and the pattern has not changed since.
  bool matches(Mat A) const;
  /// Record the (final-assembled) pattern of A; unusable (matches() false)
  /// unless A is a SeqAIJ or MPIAIJ matrix with a bs-blocked pattern and
  /// (MPIAIJ) a block local-to-global mapping.
  void record(Mat A);
  /// Between begin() and end(): A(rows, cols) += values, with rows and cols
  /// local block indices (those of the matrix's local-to-global mapping;
  /// owned rows first) and values row-major over the expanded indices.
  /// `key` names the sequence of calls (the form being assembled; nullptr:
  /// no replay): the same key replays the offsets recorded by the last
  /// complete assembly with that key on this pattern.
  void begin(Mat A, const void* key = nullptr);
  void add(std::span<const std::int32_t> rows, std::span<const std::int32_t> cols,
           std::span<const PetscScalar> values);
  void end(Mat A);
  /// End an assembly abandoned by an exception between begin() and end():
  /// the value arrays are given back, nothing is recorded or replayed.
  void cancel(Mat A) noexcept;
  /// Whether the last begin()..end() was replayed from start to end.
  bool replayed() const { return _last_replayed; }

private:
  /// A's diagonal part (A itself if serial), off-diagonal part (nullptr if
  /// serial) and the global columns of the off-diagonal part's compressed
  /// columns; aij false unless A is SeqAIJ or MPIAIJ.
  struct Parts
  {
    bool aij = false;
    int count = 0;
    Mat part[2] = {nullptr, nullptr};
    const PetscInt* garray = nullptr;
  };
  static Parts parts_of(Mat A);
  /// The local block column of each block of the off-diagonal part's
  /// compressed columns (-1: no local index on this rank); false if those
  /// columns are not bs-blocked or the column mapping's block size is not bs.
  bool off_diagonal_blocks(Mat A, const Parts& parts, std::vector<PetscInt>& block) const;
  /// Slots and strides of every owned block row from the CSR structure of
  /// the parts; false if the pattern is not bs-blocked.
  bool record_slots(const Parts& parts, const std::vector<PetscInt>& off_block);
  struct RowIJ;
  /// Slots and strides of owned block row i; false if it is not bs-blocked.
  bool record_block_row(PetscInt i, const RowIJ* ij, int nparts,
                        const std::vector<PetscInt>& off_block);
  /// Whether the current call (rows, cols) is the next recorded one.
  bool is_next_recorded_call(std::span<const std::int32_t> rows,
                             std::span<const std::int32_t> cols) const;
  /// Part and value offset of block (r, col): replayed, or searched (and
  /// recorded while recording).
  std::pair<std::int32_t, PetscInt> block_offset(std::int32_t r, std::int32_t col);
  /// Give the parts' value arrays back to PETSc.
  void restore_arrays();
  /// Block row `row` (a ghost node's) of an element matrix through PETSc.
  void add_ghost_row(PetscInt row, std::span<const std::int32_t> cols,
                     const PetscScalar* row_values);
  enum class Mode { search, record, replay };

  /// Where block (i, j) of an owned block row starts: part 0 (diagonal) or
  /// 1 (off-diagonal), at value offset `offset` (its rows _stride[part][i] apart).
  struct Slot
  {
    std::int32_t col;  ///< local block column
    std::int32_t part;
    PetscInt offset;
  };
  /// The slot of block (row, col), searched; throws outside the pattern.
  const Slot& locate(std::int32_t row, std::int32_t col) const;
  int _bs;
  PetscInt64 _id = -1;
  PetscObjectState _nonzero_state = -1;
  PetscInt _owned_rows = 0;            ///< owned block rows
  std::vector<PetscInt> _row_slots;    ///< block row i's slots: _slots[_row_slots[i]...], sorted by col
  std::vector<Slot> _slots;
  Mat _A = nullptr, _parts[2] = {nullptr, nullptr};
  PetscScalar* _values[2] = {nullptr, nullptr};
  std::vector<PetscInt> _petsc_cols; ///< columns of a ghost row handed to PETSc
  std::vector<PetscInt> _stride[2];  ///< value distance between the rows of block row i, per part

  // Replay (see above): the recorded calls' rows and columns (concatenated,
  // with the start of each call's) and the owned blocks' offsets in order.
  Mode _mode = Mode::search;
  bool _replayable = false;          ///< the pattern's offsets fit in 31 bits
  const void* _key = nullptr;        ///< key of the complete recording, nullptr: none
  const void* _current = nullptr;    ///< key of the assembly under way
  std::vector<std::int32_t> _indices;
  std::vector<std::size_t> _call_start{0};
  std::vector<std::uint32_t> _offsets;
  std::size_t _call = 0, _position = 0;
  bool _last_replayed = false;
};
} // namespace breastsim
