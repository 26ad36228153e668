// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Measures.h
 * @brief The measure of every cell of a volume mesh, summed per parent cell.
 *
 * The area of each triangle (2D) or the volume of each tetrahedron (3D), as
 * the intersectors' Prepare computes it (so the same measure the covered
 * fractions are taken of; 0 for a degenerate cell), added up per original
 * cell (MeshView::ParentOf). Extensive cell data (totals) become densities
 * by these measures before a P0 projection.
 */
#ifndef MeshProjection_Kernel_Measures_h
#define MeshProjection_Kernel_Measures_h

#include "Geometry/TetrahedronIntersector.h"
#include "Geometry/TriangleIntersector.h"
#include "Mesh/MeshView.h"

#include <vector>

namespace mp
{
template <class Intersector>
void AddParentMeasures(const MeshView& mesh, std::vector<double>& measure)
{
  typename Intersector::Cell cell;
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    if (Intersector::Prepare(mesh, c, cell))
    {
      measure[static_cast<size_t>(mesh.ParentOf(c))] += cell.Measure;
    }
  }
}

inline std::vector<double> ParentMeasures(const MeshView& mesh)
{
  std::vector<double> measure(static_cast<size_t>(mesh.Parents()), 0.0);
  if (mesh.CellDimension == 2)
  {
    AddParentMeasures<TriangleIntersector>(mesh, measure);
  }
  else
  {
    AddParentMeasures<TetrahedronIntersector>(mesh, measure);
  }
  return measure;
}
} // namespace mp

#endif
