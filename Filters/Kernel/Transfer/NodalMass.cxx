// SPDX-License-Identifier: BSD-3-Clause
#include "Transfer/NodalMass.h"

#include "Geometry/CellGeometry.h"
#include "Transfer/NodalSpace.h"

#include <algorithm>

namespace mp
{
void AssembleNodalTargetMass(std::vector<MixedBlocks>& blocks, const MeshView& mesh,
  SpaceType space, const TaskRunner& runner, CsrMatrix& matrix, const double* parentFraction,
  LargeVector<double>* cover)
{
  const Index n = SpaceSize(space, mesh);
  // Every row's diagonal, 0: adding it leaves the sums as they were.
  MixedBlocks diagonal;
  for (Index i = 0; i < n; ++i)
  {
    diagonal.Rows.push_back(i);
    diagonal.Columns.push_back(static_cast<Column>(i));
    diagonal.Values.push_back(0.0);
    diagonal.Start.push_back(i + 1);
  }
  blocks.push_back(std::move(diagonal));
  AssembleMixedMatrix(blocks, n, n, runner, matrix);
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
