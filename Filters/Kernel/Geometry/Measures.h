// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Measures.h
 * @brief The measure of every cell of a volume mesh, summed per parent cell.
 *
 * The area of each triangle (2D) or the volume of each tetrahedron (3D),
 * added up per original cell (MeshView::ParentOf). Extensive cell data
 * (totals) become densities by these measures before a P0 projection.
 */
#ifndef MeshProjection_Kernel_Measures_h
#define MeshProjection_Kernel_Measures_h

#include "Mesh/MeshView.h"

#include <cmath>
#include <vector>

namespace mp
{
inline std::vector<double> ParentMeasures(const MeshView& mesh)
{
  std::vector<double> measure(static_cast<size_t>(mesh.Parents()), 0.0);
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const Index* p = mesh.Cell(c);
    const double* x0 = mesh.Point(p[0]);
    double e[3][3] = {};
    for (int k = 0; k < mesh.CellDimension; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        e[k][a] = mesh.Point(p[k + 1])[a] - x0[a];
      }
    }
    double m;
    if (mesh.CellDimension == 2)
    {
      m = 0.5 * std::fabs(e[0][0] * e[1][1] - e[0][1] * e[1][0]);
    }
    else
    {
      m = std::fabs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
            e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
            e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
        6.0;
    }
    measure[static_cast<size_t>(mesh.ParentOf(c))] += m;
  }
  return measure;
}
} // namespace mp

#endif
