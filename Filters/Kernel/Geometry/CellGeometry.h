// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CellGeometry.h
 * @brief One simplex's measure, and the two positions of a cell made of
 *        simplices (an original cell: MeshView::ParentOf).
 *
 * SimplexGramMeasure is the measure of a simplex where no intersector is
 * prepared (the support of a hat function, the weights of a centroid):
 * |det E| / m! over its m edges E on a volume mesh, sqrt(det(E^T E)) / m!
 * on surfaces and curves (in space). On a volume mesh it is the number the
 * intersectors' Prepare gives (Measures.h: the same determinant in the
 * same operations) for every simplex whose orientation their
 * floating-point filter decides (near-degenerate ones, which they measure
 * exactly or drop, aside), and the mass matrix's SimplexMeasure
 * (MassMatrix.h, by cross products); on surfaces the three round
 * differently (the intersectors measure in the cell's frame, the mass
 * matrix by |e1 x e2|).
 *
 * A cell has two positions, for two uses:
 *
 * - CellCentroid: the measure-weighted mean of its simplices' centroids, the
 *   point where every linear function takes its mean over the cell (a
 *   reconstruction from cell averages is exact there, and conserves).
 * - CornerMean: the mean of its simplices' corners (a corner shared by two
 *   simplices counts twice), a point inside the cell that needs no measure
 *   (a cell's place in a graph, for distances between cells).
 *
 * They differ on every cell that is not one simplex (a quad split into
 * unequal triangles, a polyhedron), and on one simplex in rounding only.
 */
#ifndef MeshProjection_Kernel_CellGeometry_h
#define MeshProjection_Kernel_CellGeometry_h

#include "Mesh/MeshView.h"

#include <algorithm>
#include <cmath>

namespace mp
{
/// The edges x_a - x_0 of simplex c (CellDimension of them; coordinates beyond SpaceDimension 0).
inline void SimplexEdges(const MeshView& mesh, Index c, double (&edges)[3][3])
{
  const CellCorners corners = mesh.Cell(c);
  const double* x0 = mesh.Point(corners[0]);
  for (int a = 0; a < mesh.CellDimension; ++a)
  {
    const double* x = mesh.Point(corners[a + 1]);
    for (int i = 0; i < 3; ++i)
    {
      edges[a][i] = i < mesh.SpaceDimension ? x[i] - x0[i] : 0.0;
    }
  }
}

/// The measure (length, area, volume) of simplex c, 0 for a degenerate one.
inline double SimplexGramMeasure(const MeshView& mesh, Index c)
{
  double e[3][3];
  SimplexEdges(mesh, c, e);
  const int m = mesh.CellDimension;
  if (m == 2 && mesh.SpaceDimension == 2)
  {
    return 0.5 * std::fabs(e[0][0] * e[1][1] - e[0][1] * e[1][0]);
  }
  if (m == 3)
  {
    return std::fabs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
             e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
             e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
      6.0;
  }
  // det(E^T E) of m <= 2 edges.
  double gram[2][2] = { { 0.0, 0.0 }, { 0.0, 0.0 } };
  for (int a = 0; a < m; ++a)
  {
    for (int b = 0; b < m; ++b)
    {
      gram[a][b] = e[a][0] * e[b][0] + e[a][1] * e[b][1] + e[a][2] * e[b][2];
    }
  }
  const double determinant =
    m == 2 ? gram[0][0] * gram[1][1] - gram[0][1] * gram[1][0] : gram[0][0];
  const double factorial = m == 2 ? 2.0 : 1.0;
  return std::sqrt(std::max(0.0, determinant)) / factorial;
}

/**
 * The centroid (3 coordinates, beyond SpaceDimension 0) of the cell made
 * of simplices cells[0 .. count): the mean of their centroids weighted by
 * their measures. Returns the cell's measure. A cell of no measure (no
 * part of any integral) gets the mean of its simplices' centroids instead,
 * each simplex alike (0 for a cell of no simplex).
 */
inline double CellCentroid(const MeshView& mesh, const Index* cells, Index count, double* centroid)
{
  const int corners = mesh.CornersPerCell();
  // The weighted sum of the simplices' centroids (w x / corners per
  // corner) and the weights' sum.
  auto weighted = [&](bool measured, double* sum) {
    double total = 0.0;
    std::fill(sum, sum + 3, 0.0);
    for (Index i = 0; i < count; ++i)
    {
      const double w = measured ? SimplexGramMeasure(mesh, cells[i]) : 1.0;
      const CellCorners ids = mesh.Cell(cells[i]);
      for (int k = 0; k < corners; ++k)
      {
        const double* x = mesh.Point(ids[k]);
        for (int a = 0; a < mesh.SpaceDimension; ++a)
        {
          sum[a] += w * x[a] / corners;
        }
      }
      total += w;
    }
    return total;
  };
  double sum[3];
  const double measure = weighted(true, sum);
  double total = measure;
  if (!(measure > 0.0))
  {
    total = weighted(false, sum);
    total = total > 0.0 ? total : 1.0;
  }
  for (int a = 0; a < 3; ++a)
  {
    centroid[a] = sum[a] / total;
  }
  return measure;
}

/**
 * The mean (3 coordinates, beyond SpaceDimension 0) of the corners of the
 * simplices cells[0 .. count), each corner of each simplex once, summed in
 * the order given (0 for a cell of no simplex).
 */
inline void CornerMean(const MeshView& mesh, const Index* cells, Index count, double* position)
{
  const int corners = mesh.CornersPerCell();
  double sum[3] = { 0.0, 0.0, 0.0 };
  for (Index i = 0; i < count; ++i)
  {
    const CellCorners ids = mesh.Cell(cells[i]);
    for (int k = 0; k < corners; ++k)
    {
      for (int d = 0; d < 3; ++d)
      {
        sum[d] += mesh.Point(ids[k])[d];
      }
    }
  }
  const double n = static_cast<double>(count * corners);
  for (int d = 0; d < 3; ++d)
  {
    position[d] = count > 0 ? sum[d] / n : 0.0;
  }
}
} // namespace mp

#endif
