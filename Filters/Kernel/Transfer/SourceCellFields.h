// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SourceCellFields.h
 * @brief The given source fields on each source cell as affine functions,
 *        formed once per cell rather than once per piece.
 *
 * When the assembler sums right-hand sides (MortarAssembler::Fields), every
 * piece needs each source field on its source cell as an affine function.
 * That function is the cell's own: the field's values at the cell's
 * functions (CellDofs, reads scattered over the field arrays) times the
 * space's basis on the cell. A source cell meets several target cells, and
 * the front meets it again for each, so SourceCellFieldCache keeps the
 * functions of recently met cells about each cell's corner 0; a piece then
 * only moves the constant to its own origin (At).
 */
#ifndef MeshProjection_Kernel_SourceCellFields_h
#define MeshProjection_Kernel_SourceCellFields_h

#include "Mesh/MeshView.h"

#include <vector>

namespace mp
{
/**
 * A direct-mapped cache, by source cell id, of the source fields on a cell
 * (Space: the source space, K coefficients per function) as affine
 * functions of x - X[0] (the cell's corner 0): Components rows of K
 * coefficients, constant first. It needs the cells as the space sees them
 * to be the same for every piece of a cell (the search's own prepared
 * cells: not a surface's projected facet, nor a trace's restricted cell),
 * and the fields not to change while it is used (Clear when they do).
 */
template <class Space>
class SourceCellFieldCache
{
public:
  static constexpr int K = Space::K;
  /// At most as many slots as the search's PreparedCells (SourceWalk.h):
  /// the front meets a source cell again about as long as it keeps it
  /// prepared ...
  static constexpr Index MaxSlots = 4096;
  /// ... and fewer for many components, so that a task's cache holds at
  /// most this many coefficients (512 KiB) however many arrays are projected.
  static constexpr size_t MaxValues = size_t(1) << 16;

  /// Forgets every cell (the fields or their number of components changed).
  void Clear()
  {
    this->Ids.clear();
    this->Values.clear();
  }

  /**
   * The `components` fields given per source function in `fields`, on
   * source cell `cell` of `mesh`, as affine functions of x - cell.X[0]:
   * a pointer to components x K coefficients, valid until the next call.
   */
  template <class Cell>
  const double* Of(const MeshView& mesh, const Cell& cell, const double* fields, int components)
  {
    if (this->Ids.empty())
    {
      this->Allocate(components);
    }
    const Index slot = cell.Id & this->Mask;
    if (this->Ids[slot] != cell.Id)
    {
      this->Fill(mesh, cell, slot, fields, components);
    }
    return &this->Values[static_cast<size_t>(slot) * components * K];
  }

  /// The affine function `g` (K coefficients about p) about o = p + d instead.
  static void At(const double* g, const double (&d)[K - 1], double (&f)[K])
  {
    double constant = g[0];
    for (int a = 0; a + 1 < K; ++a)
    {
      constant += g[a + 1] * d[a];
      f[a + 1] = g[a + 1];
    }
    f[0] = constant;
  }

private:
  /// The slots, as many as fit the bound on coefficients.
  void Allocate(int components)
  {
    const size_t row = static_cast<size_t>(components) * K;
    Index slots = MaxSlots;
    while (slots > 1 && static_cast<size_t>(slots) * row > MaxValues)
    {
      slots /= 2;
    }
    this->Mask = slots - 1;
    this->Ids.assign(static_cast<size_t>(slots), -1);
    this->Values.resize(static_cast<size_t>(slots) * row);
  }

  /// Forms the functions of `cell` in `slot` (kept out of line: the front
  /// meets each cell several times, and Of's hit is its common case).
  template <class Cell>
  __attribute__((noinline)) void Fill(
    const MeshView& mesh, const Cell& cell, Index slot, const double* fields, int components)
  {
    this->Ids[slot] = cell.Id;
    double* f = &this->Values[static_cast<size_t>(slot) * components * K];
    Index dofs[Space::Dofs];
    Space::CellDofs(mesh, cell, dofs);
    double l[Space::Dofs][K];
    Space::Basis(cell, cell.X[0], l);
    for (int c = 0; c < components; ++c)
    {
      for (int k = 0; k < K; ++k)
      {
        double sum = 0.0;
        for (int j = 0; j < Space::Dofs; ++j)
        {
          sum += fields[dofs[j] * components + c] * l[j][k];
        }
        f[c * K + k] = sum;
      }
    }
  }

  Index Mask = 0;             ///< slots - 1 (a power of two), set on the first fill
  std::vector<Index> Ids;     ///< per slot: the cell whose functions it holds, or -1
  std::vector<double> Values; ///< per slot: components x K coefficients
};
} // namespace mp

#endif
