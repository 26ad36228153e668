// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MixedMatrix.h
 * @brief M_ts in compressed rows, from the blocks the search's tasks wrote.
 *
 * During the search each task appends, for every target cell it treats, one
 * block: the cell's target functions (rows), the source functions its pieces
 * met (columns, each once) and their integrals. No row is shared between
 * blocks at that time, so tasks never write the same memory. After the
 * search, AssembleMixedMatrix gathers each row from the blocks that hold it
 * (rows in concurrent ranges, columns merged through a dense accumulator)
 * and frees the blocks.
 */
#ifndef MeshProjection_Kernel_MixedMatrix_h
#define MeshProjection_Kernel_MixedMatrix_h

#include "Mesh/LargeArray.h"
#include "Mesh/Tasks.h"
#include "Transfer/CsrMatrix.h"

#include <vector>

namespace mp
{
/// The blocks of one task (see the file comment).
struct MixedBlocks
{
  int RowsPerBlock = 1;          ///< target functions per cell
  LargeVector<Index> Rows;       ///< RowsPerBlock per block
  LargeVector<Index> Start{ 0 }; ///< block b's columns: [Start[b], Start[b + 1])
  LargeVector<Column> Columns;
  /// RowsPerBlock values per column: the value of row i, column p is
  /// Values[RowsPerBlock * p + i].
  LargeVector<double> Values;

  Index Size() const { return static_cast<Index>(this->Start.size()) - 1; }
};

/**
 * M_ts (rows x columns) from the tasks' blocks, in task order; the blocks
 * are emptied. Rows hold sorted, unique columns.
 */
void AssembleMixedMatrix(std::vector<MixedBlocks>& blocks, Index rows, Index columns,
  const TaskRunner& runner, CsrMatrix& matrix);
} // namespace mp

#endif
