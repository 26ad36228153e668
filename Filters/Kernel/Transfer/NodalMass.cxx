// SPDX-License-Identifier: BSD-3-Clause
#include "Transfer/NodalMass.h"

#include "Geometry/CellGeometry.h"
#include "Transfer/NodalSpace.h"

#include <algorithm>

namespace mp
{
namespace
{
/// Adds a 0 on the diagonal of every row that lacks it (no piece met its
/// function), the columns kept sorted.
void WithDiagonal(CsrMatrix& matrix)
{
  const Index n = matrix.Rows;
  Index missing = 0;
  for (Index i = 0; i < n; ++i)
  {
    const Index p = matrix.Find(i, i);
    missing += p == matrix.RowStart[i + 1] || matrix.ColumnIndex[p] != i;
  }
  if (missing == 0)
  {
    return;
  }
  CsrMatrix with;
  with.Rows = matrix.Rows;
  with.Columns = matrix.Columns;
  with.RowStart.assign(static_cast<size_t>(n) + 1, 0);
  with.ColumnIndex.reserve(matrix.ColumnIndex.size() + static_cast<size_t>(missing));
  with.Values.reserve(with.ColumnIndex.capacity());
  for (Index i = 0; i < n; ++i)
  {
    bool placed = false;
    for (Index p = matrix.RowStart[i]; p <= matrix.RowStart[i + 1]; ++p)
    {
      const bool end = p == matrix.RowStart[i + 1];
      if (!placed && (end || matrix.ColumnIndex[p] >= i))
      {
        placed = true;
        if (end || matrix.ColumnIndex[p] != i)
        {
          with.ColumnIndex.push_back(static_cast<Column>(i));
          with.Values.push_back(0.0);
        }
      }
      if (!end)
      {
        with.ColumnIndex.push_back(matrix.ColumnIndex[p]);
        with.Values.push_back(matrix.Values[p]);
      }
    }
    with.RowStart[i + 1] = static_cast<Index>(with.ColumnIndex.size());
  }
  matrix = std::move(with);
}
} // namespace

void AssembleNodalTargetMass(std::vector<MixedBlocks>& blocks, const MeshView& mesh,
  SpaceType space, const TaskRunner& runner, CsrMatrix& matrix, const double* parentFraction,
  LargeVector<double>* cover)
{
  const Index n = SpaceSize(space, mesh);
  AssembleMixedMatrix(blocks, n, n, runner, matrix);
  WithDiagonal(matrix);
  if (cover)
  {
    cover->clear();
  }
  if (!cover || !parentFraction)
  {
    return;
  }
  cover->assign(static_cast<size_t>(n), 0.0);
  NodalFunctions f;
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    f.Bind(mesh, space, c);
    const double fraction = parentFraction[mesh.ParentOf(c)];
    for (int i = 0; i < f.Count; ++i)
    {
      (*cover)[f.Dofs[i]] = std::max((*cover)[f.Dofs[i]], fraction);
    }
  }
}

void NodalSupportCover(const MeshView& mesh, const double* parentFraction,
  std::vector<double>& covered, LargeVector<double>& whole)
{
  covered.assign(static_cast<size_t>(mesh.NumberOfPoints), 0.0);
  whole.assign(static_cast<size_t>(mesh.NumberOfPoints), 0.0);
  NodalFunctions f;
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    f.Bind(mesh, SpaceType::P1, c);
    const double measure = SimplexMeasure(mesh, c);
    const double part = measure * parentFraction[mesh.ParentOf(c)];
    for (int i = 0; i < f.Count; ++i)
    {
      whole[f.Dofs[i]] += measure;
      covered[f.Dofs[i]] += part;
    }
  }
}
} // namespace mp
