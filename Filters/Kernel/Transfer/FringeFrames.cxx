// SPDX-License-Identifier: BSD-3-Clause
// The frames a fringe stencil is fitted in (FringeFrames.h): tangent
// planes of surfaces and tangent lines of curves, from the cells around a
// point taken in an order of their geometry.
#include "Transfer/FringeFrames.h"

#include "Mesh/AlignedSum.h"
#include "Mesh/Vec3.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace mp
{
namespace
{
/// A cell around i by its other corners (one on a curve, two on a surface), sorted by their coordinates.
using OtherCorners = std::array<double, 6>;

/// x's first SpaceDimension coordinates, the others 0.
void Coordinates(const MeshView& mesh, const double* x, double* into)
{
  for (int a = 0; a < 3; ++a)
  {
    into[a] = a < mesh.SpaceDimension ? x[a] : 0.0;
  }
}

/**
 * The cells around i as their other corners, each cell's corners and the
 * cells sorted by coordinates, a cell met twice (shared by a part and its
 * halo) once.
 */
std::vector<OtherCorners> CellsByGeometry(
  const MeshView& mesh, Index i, const Index* cells, Index count)
{
  const int others = mesh.CellDimension;
  std::vector<OtherCorners> byGeometry;
  for (Index q = 0; q < count; ++q)
  {
    const CellCorners cell = mesh.Cell(cells[q]);
    OtherCorners corners{};
    int found = 0;
    for (int a = 0; a < mesh.CornersPerCell() && found < others; ++a)
    {
      if (cell[a] != i)
      {
        Coordinates(mesh, mesh.Point(cell[a]), corners.data() + 3 * found++);
      }
    }
    if (found == 2 &&
      std::lexicographical_compare(
        corners.begin() + 3, corners.begin() + 6, corners.begin(), corners.begin() + 3))
    {
      std::swap_ranges(corners.begin(), corners.begin() + 3, corners.begin() + 3);
    }
    byGeometry.push_back(corners);
  }
  std::sort(byGeometry.begin(), byGeometry.end());
  byGeometry.erase(std::unique(byGeometry.begin(), byGeometry.end()), byGeometry.end());
  return byGeometry;
}

/**
 * The sum of the cells' directions, each turned to agree with the sum so
 * far: (p - x_i) x (q - x_i) on a surface (twice the triangle's area along
 * its normal), p - x_i on a curve. Its length is 0 when they give none.
 */
void MeanDirection(
  const MeshView& mesh, const double* xi, const std::vector<OtherCorners>& byGeometry, double* sum)
{
  sum[0] = sum[1] = sum[2] = 0.0;
  for (const OtherCorners& corners : byGeometry)
  {
    double p[3], d[3];
    Sub(corners.data(), xi, p);
    if (mesh.CellDimension == 2)
    {
      double q[3];
      Sub(corners.data() + 3, xi, q);
      Cross(p, q, d);
    }
    else
    {
      std::copy(p, p + 3, d);
    }
    AddAligned(sum, d);
  }
}

/// Axes[1] and Axes[2] of `frame`: an orthonormal completion of the unit Axes[0].
void Complete(StencilFrame& frame)
{
  // The coordinate axis least along Axes[0], less its part along it, and
  // the cross product of the two.
  const double* a = frame.Axes[0];
  int least = 0;
  for (int k = 1; k < 3; ++k)
  {
    least = std::abs(a[k]) < std::abs(a[least]) ? k : least;
  }
  double* b = frame.Axes[1];
  for (int k = 0; k < 3; ++k)
  {
    b[k] = (k == least ? 1.0 : 0.0) - a[least] * a[k];
  }
  const double norm = std::sqrt(Dot(b, b));
  for (int k = 0; k < 3; ++k)
  {
    b[k] /= norm;
  }
  Cross(a, b, frame.Axes[2]);
}
} // namespace

void StencilFrame::Offset(
  const MeshView& mesh, const double* x, const double* origin, double* y) const
{
  if (this->Ambient)
  {
    for (int a = 0; a < this->Dimension; ++a)
    {
      y[a] = x[a] - origin[a];
    }
    return;
  }
  double d[3];
  for (int a = 0; a < 3; ++a)
  {
    d[a] = a < mesh.SpaceDimension ? x[a] - origin[a] : 0.0;
  }
  for (int a = 0; a < this->Dimension; ++a)
  {
    y[a] = Dot(d, this->Axes[a]);
  }
}

void StencilFrame::NormalOffset(
  const MeshView& mesh, const double* x, const double* origin, double* z) const
{
  double d[3];
  for (int a = 0; a < 3; ++a)
  {
    d[a] = a < mesh.SpaceDimension ? x[a] - origin[a] : 0.0;
  }
  for (int a = 0; a < this->Normals; ++a)
  {
    z[a] = Dot(d, this->Axes[this->Dimension + a]);
  }
}

StencilFrame StencilFrameOf(const MeshView& mesh, Index i, const Index* cells, Index count)
{
  StencilFrame frame;
  frame.Dimension = mesh.SpaceDimension;
  if (mesh.IsVolumeMesh())
  {
    return frame;
  }
  double xi[3];
  Coordinates(mesh, mesh.Point(i), xi);
  double sum[3];
  MeanDirection(mesh, xi, CellsByGeometry(mesh, i, cells, count), sum);
  const double length = std::sqrt(Dot(sum, sum));
  if (!(length > 0.0) || !std::isfinite(length))
  {
    return frame; // no tangent: the ambient frame, where no stable fit exists
  }
  frame.Ambient = false;
  frame.Dimension = mesh.CellDimension;
  frame.Normals = 3 - mesh.CellDimension;
  // A curve's tangent first, then its normals; a surface's normal last.
  const int along = mesh.CellDimension == 1 ? 0 : 2;
  for (int a = 0; a < 3; ++a)
  {
    frame.Axes[0][a] = sum[a] / length;
  }
  Complete(frame);
  if (along == 2)
  {
    // (u, v, n) from (n, u, v): the tangent axes first.
    double n[3];
    std::copy(frame.Axes[0], frame.Axes[0] + 3, n);
    std::copy(frame.Axes[1], frame.Axes[1] + 3, frame.Axes[0]);
    std::copy(frame.Axes[2], frame.Axes[2] + 3, frame.Axes[1]);
    std::copy(n, n + 3, frame.Axes[2]);
  }
  return frame;
}
} // namespace mp
