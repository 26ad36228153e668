// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/SurfaceIntersector.h"

#include "Geometry/IntersectionPieces.h"
#include "Geometry/Reach.h"
#include "Geometry/Predicates.h"
#include "Mesh/Vec3.h"

#include <algorithm>
#include <cmath>

namespace mp
{
void SurfaceIntersector::ToFrame(const Cell& frame, const double* x, double uv[2], double& height)
{
  const double d[3] = { x[0] - frame.Origin[0], x[1] - frame.Origin[1], x[2] - frame.Origin[2] };
  uv[0] = Dot(d, frame.Axis[0]);
  uv[1] = Dot(d, frame.Axis[1]);
  height = Dot(d, frame.Normal);
}

bool SurfaceIntersector::Prepare(const MeshView& mesh, Index id, Cell& cell)
{
  const CellCorners ids = mesh.Cell(id);
  cell.Id = id;
  double longest = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double* x = mesh.Point(ids[k]);
    cell.Points[k] = ids[k];
    cell.Face[k] = k;
    for (int d = 0; d < 3; ++d)
    {
      cell.Box3[2 * d] = k == 0 ? x[d] : std::min(cell.Box3[2 * d], x[d]);
      cell.Box3[2 * d + 1] = k == 0 ? x[d] : std::max(cell.Box3[2 * d + 1], x[d]);
    }
    std::copy(x, x + 3, cell.Corner[k]);
    const double* y = mesh.Point(ids[(k + 1) % 3]);
    const double e[3] = { y[0] - x[0], y[1] - x[1], y[2] - x[2] };
    longest = std::max(longest, std::sqrt(Dot(e, e)));
  }
  const double* x0 = cell.Corner[0];
  const double* x1 = cell.Corner[1];
  const double* x2 = cell.Corner[2];
  double a[3];
  double b[3];
  double n[3];
  Sub(x1, x0, a);
  Sub(x2, x0, b);
  Cross(a, b, n);
  const double nn = std::sqrt(Dot(n, n));
  const double la = std::sqrt(Dot(a, a));
  if (!(nn > 0.0) || !(la > 0.0) || !std::isfinite(nn) || !std::isfinite(la))
  {
    return false;
  }
  for (int d = 0; d < 3; ++d)
  {
    cell.Origin[d] = x0[d];
    cell.Normal[d] = n[d] / nn;
    cell.Axis[0][d] = a[d] / la;
  }
  // Second axis: normal x first axis, unit by construction (up to rounding).
  Cross(cell.Normal, cell.Axis[0], cell.Axis[1]);
  for (int k = 0; k < 3; ++k)
  {
    double h;
    ToFrame(cell, cell.Corner[k], cell.X[k], h);
  }
  cell.Reach = mesh.SurfaceReach * longest;
  cell.MinCosine = mesh.SurfaceMinCosine;
  cell.Orientation = mesh.SurfaceOrientation;
  // Counterclockwise in its own frame by construction, unless rounding
  // flattened it: PrepareCorners then rejects or reorders, and the normal
  // must follow the order it keeps.
  if (!TriangleIntersector::PrepareCorners(cell))
  {
    return false;
  }
  return cell.Face[1] == 1; // a swap means a triangle too thin to have a normal
}

void SurfaceIntersector::Bounds(const Cell& cell, double box[6])
{
  WidenBox(cell.Box3, cell.Reach, box);
}

void SurfaceIntersector::Center(const Cell& cell, double q[3])
{
  // The frame's image of the plane's centre (the corners' mean).
  const double u = (cell.X[0][0] + cell.X[1][0] + cell.X[2][0]) / 3.0;
  const double v = (cell.X[0][1] + cell.X[1][1] + cell.X[2][1]) / 3.0;
  for (int d = 0; d < 3; ++d)
  {
    q[d] = cell.Origin[d] + u * cell.Axis[0][d] + v * cell.Axis[1][d];
  }
}

int SurfaceIntersector::Locate(const Cell& cell, const double* q, int first)
{
  double uv[2];
  double h;
  ToFrame(cell, q, uv, h);
  return TriangleIntersector::Locate(cell, uv, first);
}

bool SurfaceIntersector::Intersect(const Cell& t, const Cell& s, Piece& piece)
{
  piece.NumberOfVertices = 0;
  piece.TouchedFaces = 0;
  piece.SourceFaces = 0;
  piece.Target = &t;
  piece.Screened = false;
  if (!BoxesWithinReach(t.Box3, s.Box3, t.Reach))
  {
    return false;
  }
  // From here on a rejection screens out a facet near the target.
  piece.Screened = true;
  const double dot = Dot(t.Normal, s.Normal);
  const double cosine = t.Orientation == 0 ? dot : (t.Orientation == 1 ? -dot : std::fabs(dot));
  if (cosine < t.MinCosine)
  {
    return false; // facing away, or across a sharp edge
  }
  // A source facing the other way has a clockwise image: its corners 1 and
  // 2 are taken in turn (and its faces with them).
  const bool reversed = t.Orientation == 1 || (t.Orientation == 2 && dot < 0.0);
  const int order[3] = { 0, reversed ? 2 : 1, reversed ? 1 : 2 };
  // The source corners in the target's frame, from the mesh's own points:
  // a point shared by two source facets has one image.
  TriangleIntersector::Cell& p = piece.Projected;
  p.Id = s.Id;
  double height[3];
  for (int k = 0; k < 3; ++k)
  {
    const int from = order[k];
    p.Points[k] = s.Points[from];
    p.Face[k] = s.Face[from];
    ToFrame(t, s.Corner[from], p.X[k], height[k]);
  }
  const double reach = t.Reach;
  if (std::min({ height[0], height[1], height[2] }) > reach ||
    std::max({ height[0], height[1], height[2] }) < -reach)
  {
    return false;
  }
  // The normals' angle is below 90 degrees, so the image keeps the
  // source's orientation unless rounding flattens it: then it meets nothing.
  if (!(Orient2D(p.X[0], p.X[1], p.X[2]) > 0.0) || !TriangleIntersector::PrepareCorners(p))
  {
    return false;
  }
  if (!TriangleIntersector::Intersect(t, p, piece))
  {
    piece.Screened = false; // near, but its image misses the target
    return false;
  }
  // The source facet's height over the target plane is affine on the
  // image: it must stay within reach over the whole piece (its vertices).
  const double dh1 = height[1] - height[0];
  const double dh2 = height[2] - height[0];
  for (int v = 0; v < piece.NumberOfVertices; ++v)
  {
    const double x = piece.X[v][0] - p.X[0][0];
    const double y = piece.X[v][1] - p.X[0][1];
    const double l1 = p.Inverse[0][0] * x + p.Inverse[0][1] * y;
    const double l2 = p.Inverse[1][0] * x + p.Inverse[1][1] * y;
    if (std::fabs(height[0] + l1 * dh1 + l2 * dh2) > reach)
    {
      piece.NumberOfVertices = 0;
      piece.TouchedFaces = 0;
      piece.SourceFaces = 0;
      return false;
    }
  }
  if (reversed)
  {
    // The source faces were found in the image's order: back to the cell's.
    unsigned faces = 0;
    for (int k = 0; k < 3; ++k)
    {
      faces |= ((piece.SourceFaces >> k) & 1u) << p.Face[k];
    }
    piece.SourceFaces = faces;
  }
  piece.Screened = false;
  return true;
}

void SurfaceIntersector::AppendPiece(
  const Piece& piece, Index target, Index source, IntersectionPieces& pieces)
{
  AppendPolygon(*piece.Target, piece, target, source, pieces);
}

void SurfaceIntersector::AppendPolygon(const Cell& t, const TriangleIntersector::Piece& polygon,
  Index target, Index source, IntersectionPieces& pieces)
{
  for (int v = 0; v < polygon.NumberOfVertices; ++v)
  {
    for (int d = 0; d < 3; ++d)
    {
      pieces.Points.push_back(
        t.Origin[d] + polygon.X[v][0] * t.Axis[0][d] + polygon.X[v][1] * t.Axis[1][d]);
    }
  }
  pieces.Offsets.push_back(pieces.Offsets.back() + polygon.NumberOfVertices);
  pieces.TargetCell.push_back(target);
  pieces.SourceCell.push_back(source);
  pieces.Measure.push_back(TriangleIntersector::Measure(polygon));
}
} // namespace mp
