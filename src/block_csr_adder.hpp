#pragma once
// Fast addition of element matrices into an assembled serial PETSc AIJ matrix
// whose nonzero pattern is made of bs x bs blocks (vector P1/P2 spaces).
//
// PETSc's MatSetValuesBlockedLocal on AIJ expands every element matrix into
// scalar rows and binary-searches each of the (n bs)^2 columns; that was 75 %
// of the Jacobian assembly (52k P1 tetrahedra: 0.12 of 0.16 s). Here one
// search per block pair finds the block's offset in the CSR row, and the bs^2
// values are added straight into the value array.
#include <petscmat.h>
#include <cstdint>
#include <span>
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
  /// unless A is a SeqAIJ matrix with a bs-blocked pattern.
  void record(Mat A);
  /// Between begin() and end(): A(rows, cols) += values, with rows and cols
  /// block indices and values row-major over the expanded (scalar) indices.
  void begin(Mat A);
  void add(std::span<const std::int32_t> rows, std::span<const std::int32_t> cols,
           std::span<const PetscScalar> values);
  void end(Mat A);

private:
  int _bs;
  PetscInt64 _id = -1;
  PetscObjectState _nonzero_state = -1;
  std::vector<PetscInt> _row_start;    ///< CSR offset of scalar row bs*i
  std::vector<PetscInt> _row_length;   ///< entries per scalar row of block row i
  std::vector<PetscInt> _block_start;  ///< block row i's columns: _block_cols[_block_start[i]...]
  std::vector<std::int32_t> _block_cols;
  PetscScalar* _values = nullptr;
};
} // namespace breastsim
