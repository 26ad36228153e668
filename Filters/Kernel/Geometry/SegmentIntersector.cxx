// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/SegmentIntersector.h"

#include "Geometry/IntersectionPieces.h"
#include "Geometry/Reach.h"

#include <algorithm>
#include <cmath>

namespace mp
{
double SegmentIntersector::ToFrame(const Cell& frame, const double* x, double offset[3])
{
  const double d[3] = { x[0] - frame.Origin[0], x[1] - frame.Origin[1], x[2] - frame.Origin[2] };
  const double u = d[0] * frame.Axis[0] + d[1] * frame.Axis[1] + d[2] * frame.Axis[2];
  for (int a = 0; a < 3; ++a)
  {
    offset[a] = d[a] - u * frame.Axis[a];
  }
  return u;
}

bool SegmentIntersector::Prepare(const MeshView& mesh, Index id, Cell& cell)
{
  const CellCorners ids = mesh.Cell(id);
  cell.Id = id;
  const double* a = mesh.Point(ids[0]);
  const double* b = mesh.Point(ids[1]);
  double e[3];
  double length2 = 0.0;
  for (int d = 0; d < 3; ++d)
  {
    // A curve in the plane has z = 0 (SpaceDimension 2): the same formula.
    e[d] = b[d] - a[d];
    length2 += e[d] * e[d];
    cell.Origin[d] = a[d];
    cell.Corner[0][d] = a[d];
    cell.Corner[1][d] = b[d];
    cell.Box3[2 * d] = std::min(a[d], b[d]);
    cell.Box3[2 * d + 1] = std::max(a[d], b[d]);
  }
  const double length = std::sqrt(length2);
  if (!(length > 0.0) || !std::isfinite(length))
  {
    return false;
  }
  for (int d = 0; d < 3; ++d)
  {
    cell.Axis[d] = e[d] / length;
  }
  cell.Points[0] = ids[0];
  cell.Points[1] = ids[1];
  cell.Face[0] = 0;
  cell.Face[1] = 1;
  double offset[3];
  cell.X[0][0] = 0.0;
  cell.X[1][0] = ToFrame(cell, b, offset);
  cell.Measure = cell.X[1][0];
  cell.Inverse[0][0] = 1.0 / cell.Measure;
  cell.Reach = mesh.SurfaceReach * length;
  cell.MinCosine = mesh.SurfaceMinCosine;
  return cell.Measure > 0.0 && std::isfinite(cell.Inverse[0][0]);
}

void SegmentIntersector::Bounds(const Cell& cell, double box[6])
{
  WidenBox(cell.Box3, cell.Reach, box);
}

void SegmentIntersector::Center(const Cell& cell, double q[3])
{
  for (int d = 0; d < 3; ++d)
  {
    q[d] = 0.5 * (cell.Corner[0][d] + cell.Corner[1][d]);
  }
}

int SegmentIntersector::Locate(const Cell& cell, const double* q, int)
{
  double offset[3];
  const double u = ToFrame(cell, q, offset);
  // Beyond corner 0: across face 1 (the point of corner 0); beyond corner 1: face 0.
  return u < cell.X[0][0] ? 1 : (u > cell.X[1][0] ? 0 : -1);
}

bool SegmentIntersector::Intersect(const Cell& t, const Cell& s, Piece& piece)
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
  piece.Screened = true; // from here on, a rejection screens out a segment near the target
  const double cosine = t.Axis[0] * s.Axis[0] + t.Axis[1] * s.Axis[1] + t.Axis[2] * s.Axis[2];
  if (std::fabs(cosine) < t.MinCosine)
  {
    return false;
  }
  // The source's corners on the target's axis, in increasing order.
  Cell& p = piece.Projected;
  p.Id = s.Id;
  double offset[2][3];
  double u[2];
  for (int k = 0; k < 2; ++k)
  {
    u[k] = ToFrame(t, s.Corner[k], offset[k]);
  }
  if (!(u[0] != u[1]))
  {
    return false; // the image is a point
  }
  const int first = u[0] < u[1] ? 0 : 1;
  for (int k = 0; k < 2; ++k)
  {
    const int from = k == 0 ? first : 1 - first;
    p.Points[k] = s.Points[from];
    p.Face[k] = s.Face[from];
    p.X[k][0] = u[from];
    std::copy(s.Corner[from], s.Corner[from] + 3, p.Corner[k]);
  }
  p.Measure = p.X[1][0] - p.X[0][0];
  p.Inverse[0][0] = 1.0 / p.Measure;
  const double lo = std::max(t.X[0][0], p.X[0][0]);
  const double hi = std::min(t.X[1][0], p.X[1][0]);
  if (lo > hi)
  {
    piece.Screened = false; // near, but its image misses the target
    return false;
  }
  // The source's distance from the target's line is convex along it: its
  // largest over the piece is at one of the piece's ends.
  for (const double x : { lo, hi })
  {
    const double l = (x - p.X[0][0]) / p.Measure; // toward the image's corner 1
    const double* a = offset[first];
    const double* b = offset[1 - first];
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      const double o = (1.0 - l) * a[d] + l * b[d];
      d2 += o * o;
    }
    if (!(d2 <= t.Reach * t.Reach))
    {
      return false;
    }
  }
  piece.Screened = false;
  piece.NumberOfVertices = lo < hi ? 2 : 1;
  piece.X[0][0] = lo;
  piece.X[1][0] = hi;
  // Face k of the target is its corner 1 - k: it lies on the source when the
  // closed image holds it.
  for (int k = 0; k < 2; ++k)
  {
    const double corner = t.X[1 - k][0];
    if (p.X[0][0] <= corner && corner <= p.X[1][0])
    {
      piece.TouchedFaces |= 1u << k;
    }
  }
  // Face l of the source (Cell order) is its corner 1 - l.
  for (int l = 0; l < 2; ++l)
  {
    if (lo <= u[1 - l] && u[1 - l] <= hi)
    {
      piece.SourceFaces |= 1u << l;
    }
  }
  return true;
}

double SegmentIntersector::Measure(const Piece& piece)
{
  return piece.NumberOfVertices == 2 ? piece.X[1][0] - piece.X[0][0] : 0.0;
}

double SegmentIntersector::Moments(const Piece& piece, double (&origin)[1], double (&M)[2][2])
{
  return IntervalMoments(piece.NumberOfVertices, piece.X, origin, M);
}

double SegmentIntersector::IntervalMoments(
  int n, const double (&X)[2][1], double (&origin)[1], double (&M)[2][2])
{
  const double length = n == 2 ? X[1][0] - X[0][0] : 0.0;
  if (!(length > 0.0))
  {
    return 0.0;
  }
  origin[0] = X[0][0];
  M[0][0] = length;
  M[0][1] = M[1][0] = 0.5 * length * length;
  M[1][1] = length * length * length / 3.0;
  return length;
}

void SegmentIntersector::AppendPiece(
  const Piece& piece, Index target, Index source, IntersectionPieces& pieces)
{
  AppendInterval(*piece.Target, piece.NumberOfVertices, piece.X, target, source, pieces);
}

void SegmentIntersector::AppendInterval(const Cell& t, int n, const double (&X)[2][1], Index target,
  Index source, IntersectionPieces& pieces)
{
  for (int v = 0; v < n; ++v)
  {
    for (int d = 0; d < 3; ++d)
    {
      pieces.Points.push_back(t.Origin[d] + X[v][0] * t.Axis[d]);
    }
  }
  pieces.Offsets.push_back(pieces.Offsets.back() + n);
  pieces.TargetCell.push_back(target);
  pieces.SourceCell.push_back(source);
  pieces.Measure.push_back(n == 2 ? X[1][0] - X[0][0] : 0.0);
}
} // namespace mp
