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

#include <algorithm>
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
template <class Intersector>
void AddParentCover(const MeshView& mesh, const std::vector<double>& fraction,
  std::vector<double>& measure, std::vector<double>& covered)
{
  typename Intersector::Cell cell;
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    if (Intersector::Prepare(mesh, c, cell))
    {
      const size_t p = static_cast<size_t>(mesh.ParentOf(c));
      measure[p] += cell.Measure;
      covered[p] += fraction[static_cast<size_t>(c)] * cell.Measure;
    }
  }
}

/// Per original cell, the covered fraction of its measure, from the
/// covered fraction of each of its simplices.
inline std::vector<double> ParentFractions(const MeshView& mesh, const std::vector<double>& fraction)
{
  std::vector<double> measure(static_cast<size_t>(mesh.Parents()), 0.0);
  std::vector<double> covered(measure.size(), 0.0);
  if (mesh.CellDimension == 2)
  {
    AddParentCover<TriangleIntersector>(mesh, fraction, measure, covered);
  }
  else
  {
    AddParentCover<TetrahedronIntersector>(mesh, fraction, measure, covered);
  }
  for (size_t p = 0; p < measure.size(); ++p)
  {
    covered[p] = measure[p] > 0.0 ? std::min(1.0, covered[p] / measure[p]) : 0.0;
  }
  return covered;
}
} // namespace mp

#endif
