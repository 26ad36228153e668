// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CellGeometry.h
 * @brief The simplex measure, and the two positions of a cell made of
 *        simplices (an original cell: MeshView::ParentOf).
 *
 * SimplexMeasure is the one measure of a simplex where no intersector is
 * prepared: the mass matrix's cells (MassMatrix.h), the support of a hat
 * function (FringeAggregation.h), the weights of a centroid. On a volume
 * mesh it is, bit for bit, the number the intersectors' Prepare gives
 * (Measures.h: the same determinant in the same operations) for every
 * simplex whose orientation their floating-point filter decides; they keep
 * their own for the near-degenerate ones (measured exactly, or dropped)
 * and for surfaces (measured in the cell's own frame, where they clip).
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
#include "Mesh/Vec3.h"

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

/**
 * The measure (length, area, volume) of simplex c, without sign: |e_0| on
 * a curve, |e_0 x e_1| / 2 on a triangle (in the plane or in space), and
 * |e_0 . (e_1 x e_2)| / 6 on a tetrahedron, over its edges e_a. The cross
 * product keeps a thin triangle in space accurate where the Gram
 * determinant's difference of products would cancel.
 */
inline double SimplexMeasure(const MeshView& mesh, Index c)
{
  double e[3][3];
  SimplexEdges(mesh, c, e);
  double n[3];
  switch (mesh.CellDimension)
  {
    case 1:
      return std::sqrt(Dot(e[0], e[0]));
    case 2:
      Cross(e[0], e[1], n);
      return 0.5 * std::sqrt(Dot(n, n));
    default:
      Cross(e[1], e[2], n);
      return std::fabs(Dot(e[0], n)) / 6.0;
  }
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
      const double w = measured ? SimplexMeasure(mesh, cells[i]) : 1.0;
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
