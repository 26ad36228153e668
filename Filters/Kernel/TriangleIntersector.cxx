// SPDX-License-Identifier: BSD-3-Clause
#include "TriangleIntersector.h"

#include "MortarBlocks.h"
#include "MortarProjector.h"
#include "Predicates.h"

#include <algorithm>
#include <cmath>

namespace mp
{
namespace
{
// A monotone function of the angle of (dx, dy), in [0, 4): cheaper than
// atan2 and enough to order points around an interior point.
inline double PseudoAngle(double dx, double dy)
{
  const double r = std::fabs(dx) + std::fabs(dy);
  if (r == 0.0)
  {
    return 0.0;
  }
  const double p = dy / r;
  if (dx < 0.0)
  {
    return 2.0 - p;
  }
  return dy < 0.0 ? 4.0 + p : p;
}


// Orders the points counterclockwise around their mean and drops exact
// duplicates (a corner of one triangle that is also a corner of the other).
void SortAndRemoveDoubles(TriangleIntersector::Piece& p)
{
  const int n = p.NumberOfVertices;
  if (n < 2)
  {
    return;
  }
  double cx = 0.0;
  double cy = 0.0;
  for (int i = 0; i < n; ++i)
  {
    cx += p.X[i][0];
    cy += p.X[i][1];
  }
  cx /= n;
  cy /= n;
  double key[TriangleIntersector::MaxPolygonVertices];
  for (int i = 0; i < n; ++i)
  {
    key[i] = PseudoAngle(p.X[i][0] - cx, p.X[i][1] - cy);
  }
  for (int i = 1; i < n; ++i) // insertion sort: n <= 12
  {
    const double k = key[i];
    const double x = p.X[i][0];
    const double y = p.X[i][1];
    int j = i - 1;
    while (j >= 0 && key[j] > k)
    {
      key[j + 1] = key[j];
      p.X[j + 1][0] = p.X[j][0];
      p.X[j + 1][1] = p.X[j][1];
      --j;
    }
    key[j + 1] = k;
    p.X[j + 1][0] = x;
    p.X[j + 1][1] = y;
  }
  int m = 0;
  for (int i = 0; i < n; ++i)
  {
    bool duplicate = false;
    for (int j = 0; j < m && !duplicate; ++j)
    {
      duplicate = p.X[j][0] == p.X[i][0] && p.X[j][1] == p.X[i][1];
    }
    if (!duplicate)
    {
      p.X[m][0] = p.X[i][0];
      p.X[m][1] = p.X[i][1];
      ++m;
    }
  }
  p.NumberOfVertices = m;
}

inline void AddVertex(TriangleIntersector::Piece& p, double x, double y)
{
  p.X[p.NumberOfVertices][0] = x;
  p.X[p.NumberOfVertices][1] = y;
  ++p.NumberOfVertices;
}
} // namespace

bool TriangleIntersector::Prepare(const MeshView& mesh, Index id, Cell& cell)
{
  const Index* ids = mesh.Cell(id);
  cell.Id = id;
  for (int k = 0; k < 3; ++k)
  {
    const double* x = mesh.Point(ids[k]);
    cell.Points[k] = ids[k];
    cell.Face[k] = k;
    cell.X[k][0] = x[0];
    cell.X[k][1] = x[1];
  }
  double twiceArea = Orient2D(cell.X[0], cell.X[1], cell.X[2]);
  if (!(twiceArea != 0.0) || !std::isfinite(twiceArea))
  {
    return false;
  }
  if (twiceArea < 0.0) // clockwise: swap corners 1 and 2 (and their faces)
  {
    std::swap(cell.Points[1], cell.Points[2]);
    std::swap(cell.Face[1], cell.Face[2]);
    std::swap(cell.X[1][0], cell.X[2][0]);
    std::swap(cell.X[1][1], cell.X[2][1]);
    twiceArea = -twiceArea;
  }
  cell.Box[0] = std::min({ cell.X[0][0], cell.X[1][0], cell.X[2][0] });
  cell.Box[1] = std::max({ cell.X[0][0], cell.X[1][0], cell.X[2][0] });
  cell.Box[2] = std::min({ cell.X[0][1], cell.X[1][1], cell.X[2][1] });
  cell.Box[3] = std::max({ cell.X[0][1], cell.X[1][1], cell.X[2][1] });
  // Jacobian J = [X1 - X0, X2 - X0]; barycentrics 1, 2 = J^-1 (x - X0).
  const double j00 = cell.X[1][0] - cell.X[0][0];
  const double j01 = cell.X[2][0] - cell.X[0][0];
  const double j10 = cell.X[1][1] - cell.X[0][1];
  const double j11 = cell.X[2][1] - cell.X[0][1];
  const double det = j00 * j11 - j01 * j10;
  cell.Measure = 0.5 * std::fabs(det);
  cell.Inverse[0][0] = j11 / det;
  cell.Inverse[0][1] = -j01 / det;
  cell.Inverse[1][0] = -j10 / det;
  cell.Inverse[1][1] = j00 / det;
  return cell.Measure > 0.0 && std::isfinite(cell.Inverse[0][0] + cell.Inverse[0][1] +
                                 cell.Inverse[1][0] + cell.Inverse[1][1]);
}

void TriangleIntersector::Bounds(const Cell& cell, double box[6])
{
  box[0] = cell.Box[0];
  box[1] = cell.Box[1];
  box[2] = cell.Box[2];
  box[3] = cell.Box[3];
  box[4] = 0.0;
  box[5] = 0.0;
}

bool TriangleIntersector::Intersect(const Cell& t, const Cell& s, Piece& piece)
{
  piece.NumberOfVertices = 0;
  piece.TouchedFaces = 0;
  piece.SourceFaces = 0;
  // Cheap rejection (the paper's conclusion): disjoint closed bounding boxes.
  if (t.Box[1] < s.Box[0] || s.Box[1] < t.Box[0] || t.Box[3] < s.Box[2] || s.Box[3] < t.Box[2])
  {
    return false;
  }

  // ot[k][j]: side of source corner j w.r.t. target edge k (corners k+1, k+2),
  // os[l][i]: side of target corner i w.r.t. source edge l. Positive = inside.
  double ot[3][3];
  double os[3][3];
  for (int k = 0; k < 3; ++k)
  {
    const double* a = t.X[(k + 1) % 3];
    const double* b = t.X[(k + 2) % 3];
    const double* c = s.X[(k + 1) % 3];
    const double* d = s.X[(k + 2) % 3];
    for (int j = 0; j < 3; ++j)
    {
      ot[k][j] = Orient2D(a, b, s.X[j]);
      os[k][j] = Orient2D(c, d, t.X[j]);
    }
  }

  // Separating edge: all three corners of the other cell strictly outside.
  for (int k = 0; k < 3; ++k)
  {
    if ((ot[k][0] < 0.0 && ot[k][1] < 0.0 && ot[k][2] < 0.0) ||
      (os[k][0] < 0.0 && os[k][1] < 0.0 && os[k][2] < 0.0))
    {
      return false;
    }
  }

  // Corners of the target in the closed source: they lie on the two target
  // faces that meet at that corner.
  for (int i = 0; i < 3; ++i)
  {
    if (os[0][i] >= 0.0 && os[1][i] >= 0.0 && os[2][i] >= 0.0)
    {
      AddVertex(piece, t.X[i][0], t.X[i][1]);
      piece.TouchedFaces |= (7u & ~(1u << i));
      for (int l = 0; l < 3; ++l)
      {
        if (os[l][i] == 0.0) // on source edge l
        {
          piece.SourceFaces |= 1u << l;
        }
      }
    }
  }
  // Corners of the source in the closed target; one on target edge k
  // touches face k.
  for (int j = 0; j < 3; ++j)
  {
    if (ot[0][j] >= 0.0 && ot[1][j] >= 0.0 && ot[2][j] >= 0.0)
    {
      AddVertex(piece, s.X[j][0], s.X[j][1]);
      piece.SourceFaces |= (7u & ~(1u << j)); // the source edges at corner j
      for (int k = 0; k < 3; ++k)
      {
        if (ot[k][j] == 0.0)
        {
          piece.TouchedFaces |= 1u << k;
        }
      }
    }
  }
  // Proper crossings: both pairs of end points strictly on opposite sides.
  // Every touching configuration is already covered by the corner tests.
  for (int k = 0; k < 3; ++k)
  {
    for (int l = 0; l < 3; ++l)
    {
      const double oc = ot[k][(l + 1) % 3];
      const double od = ot[k][(l + 2) % 3];
      const double oa = os[l][(k + 1) % 3];
      const double ob = os[l][(k + 2) % 3];
      if (((oc > 0.0 && od < 0.0) || (oc < 0.0 && od > 0.0)) &&
        ((oa > 0.0 && ob < 0.0) || (oa < 0.0 && ob > 0.0)))
      {
        const double* c = s.X[(l + 1) % 3];
        const double* d = s.X[(l + 2) % 3];
        const double u = oc / (oc - od);
        AddVertex(piece, c[0] + u * (d[0] - c[0]), c[1] + u * (d[1] - c[1]));
        piece.TouchedFaces |= 1u << k;
        piece.SourceFaces |= 1u << l;
      }
    }
  }
  if (piece.NumberOfVertices == 0)
  {
    return false;
  }
  SortAndRemoveDoubles(piece);
  return true;
}

double TriangleIntersector::Measure(const Piece& p)
{
  double twice = 0.0;
  for (int i = 1; i + 1 < p.NumberOfVertices; ++i)
  {
    const double ax = p.X[i][0] - p.X[0][0];
    const double ay = p.X[i][1] - p.X[0][1];
    const double bx = p.X[i + 1][0] - p.X[0][0];
    const double by = p.X[i + 1][1] - p.X[0][1];
    twice += ax * by - ay * bx;
  }
  return 0.5 * twice;
}

double TriangleIntersector::Integrate(
  const Piece& p, const Cell& t, const Cell& s, double Mts[3][3], double Mtt[3][3])
{
  // Moments of the polygon (1, x, y, x^2, xy, y^2) relative to its first
  // vertex, edge by edge (Green's theorem): exact for any polygon. A local
  // origin inside both cells keeps the barycentric functions below of size
  // 1 over the piece, so that thin cells cannot make them cancel.
  if (p.NumberOfVertices < 3)
  {
    return 0.0;
  }
  const double ox = p.X[0][0];
  const double oy = p.X[0][1];
  double m0 = 0, mx = 0, my = 0, mxx = 0, mxy = 0, myy = 0;
  for (int i = 1; i + 1 < p.NumberOfVertices; ++i)
  {
    const int j = i + 1;
    const double px = p.X[i][0] - ox;
    const double py = p.X[i][1] - oy;
    const double qx = p.X[j][0] - ox;
    const double qy = p.X[j][1] - oy;
    const double cross = px * qy - py * qx;
    m0 += cross;
    mx += cross * (px + qx);
    my += cross * (py + qy);
    mxx += cross * (px * px + px * qx + qx * qx);
    myy += cross * (py * py + py * qy + qy * qy);
    mxy += cross * (2 * px * py + px * qy + qx * py + 2 * qx * qy);
  }
  m0 /= 2;
  mx /= 6;
  my /= 6;
  mxx /= 12;
  myy /= 12;
  mxy /= 24;
  if (!(m0 > 0.0))
  {
    return 0.0; // rounding of a sliver
  }
  // Barycentric coordinates as affine functions a + b x + c y of the local
  // coordinates, for the target and the source.
  double lt[3][3];
  double ls[3][3];
  for (int side = 0; side < 2; ++side)
  {
    const Cell& c = side == 0 ? t : s;
    double(&l)[3][3] = side == 0 ? lt : ls;
    const double dx = ox - c.X[0][0];
    const double dy = oy - c.X[0][1];
    for (int r = 0; r < 2; ++r)
    {
      l[r + 1][0] = c.Inverse[r][0] * dx + c.Inverse[r][1] * dy;
      l[r + 1][1] = c.Inverse[r][0];
      l[r + 1][2] = c.Inverse[r][1];
    }
    for (int k = 0; k < 3; ++k)
    {
      l[0][k] = (k == 0 ? 1.0 : 0.0) - l[1][k] - l[2][k];
    }
  }
  // Integral of (a + b x + c y)(a' + b' x + c' y) from the moments.
  auto product = [&](const double* f, const double* g) {
    return f[0] * g[0] * m0 + (f[0] * g[1] + f[1] * g[0]) * mx + (f[0] * g[2] + f[2] * g[0]) * my +
      f[1] * g[1] * mxx + (f[1] * g[2] + f[2] * g[1]) * mxy + f[2] * g[2] * myy;
  };
  AddMortarBlocks<3>(lt, ls, product, Mts, Mtt);
  return m0;
}

void TriangleIntersector::Append(
  const Piece& p, Index target, Index source, double area, IntersectionPieces& pieces)
{
  for (int v = 0; v < p.NumberOfVertices; ++v)
  {
    pieces.Points.insert(pieces.Points.end(), { p.X[v][0], p.X[v][1], 0.0 });
  }
  pieces.Offsets.push_back(pieces.Offsets.back() + p.NumberOfVertices);
  pieces.TargetCell.push_back(target);
  pieces.SourceCell.push_back(source);
  pieces.Measure.push_back(area);
}
} // namespace mp
