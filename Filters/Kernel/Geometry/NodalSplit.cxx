// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/NodalSplit.h"

#include "Geometry/Predicates.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace mp
{
namespace
{
/// A cell whose corners are cut off (Tetra10, Hexa20, Wedge15, Pyramid13):
/// its corners, its edges (the mid node of edge e is node corners + e, as
/// in VTK's numbering) and its faces (corner loops, outward). Outward for
/// the orientation of VTK's parametric coordinates, in which a wedge's
/// triangle 0 1 2 turns counterclockwise seen from 3 4 5 (CellSplit's
/// linear wedge table has it the other way).
struct CornerCutCell
{
  int Corners;
  std::vector<std::array<int, 2>> Edges;
  std::vector<std::vector<int>> Faces;
};

const CornerCutCell& CornerCutTable(NodalType type)
{
  static const CornerCutCell tetra{ 4,
    { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 3 }, { 2, 3 } },
    { { 0, 2, 1 }, { 0, 1, 3 }, { 1, 2, 3 }, { 0, 3, 2 } } };
  static const CornerCutCell hexa{ 8,
    { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 4, 5 }, { 5, 6 }, { 6, 7 }, { 7, 4 }, { 0, 4 },
      { 1, 5 }, { 2, 6 }, { 3, 7 } },
    { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 }, { 1, 2, 6, 5 }, { 2, 3, 7, 6 },
      { 3, 0, 4, 7 } } };
  static const CornerCutCell wedge{ 6,
    { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 3, 4 }, { 4, 5 }, { 5, 3 }, { 0, 3 }, { 1, 4 }, { 2, 5 } },
    { { 0, 2, 1 }, { 3, 4, 5 }, { 0, 1, 4, 3 }, { 1, 2, 5, 4 }, { 2, 0, 3, 5 } } };
  static const CornerCutCell pyramid{ 5,
    { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 4 }, { 1, 4 }, { 2, 4 }, { 3, 4 } },
    { { 0, 3, 2, 1 }, { 0, 1, 4 }, { 1, 2, 4 }, { 2, 3, 4 }, { 3, 0, 4 } } };
  switch (type)
  {
    case NodalType::Hexa20:
      return hexa;
    case NodalType::Wedge15:
      return wedge;
    case NodalType::Pyramid13:
      return pyramid;
    default:
      return tetra;
  }
}

/// The largest extent of the nodes' bounding box.
double Size(const double* points, const Index* nodes, int n)
{
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = hi[d] = points[3 * nodes[0] + d];
  }
  for (int k = 1; k < n; ++k)
  {
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min(lo[d], points[3 * nodes[k] + d]);
      hi[d] = std::max(hi[d], points[3 * nodes[k] + d]);
    }
  }
  return std::max({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2] });
}

/**
 * The corner cuts and the polyhedron that remains, for a CornerCutCell:
 * the corner tetrahedra (positive for a positive cell) appended to
 * `tetrahedra`, the apex pyramid of a 4-edge corner appended to `pyramids`
 * (base loop then apex, VTK's pyramid order), and the remaining
 * polyhedron's outward faces as a face stream (without the count).
 * Returns the number of faces.
 */
int CutCorners(const CornerCutCell& cell, const Index* nodes, std::vector<Index>& tetrahedra,
  std::vector<Index>& pyramids, std::vector<Index>& stream)
{
  auto mid = [&](int a, int b) {
    for (size_t e = 0; e < cell.Edges.size(); ++e)
    {
      if ((cell.Edges[e][0] == a && cell.Edges[e][1] == b) ||
        (cell.Edges[e][0] == b && cell.Edges[e][1] == a))
      {
        return nodes[cell.Corners + static_cast<int>(e)];
      }
    }
    return Index(-1); // not reached: the tables' faces run along their edges
  };
  int nfaces = 0;
  // Each cell face's mid-edge nodes, in the face's (outward) order.
  for (const std::vector<int>& face : cell.Faces)
  {
    const int n = static_cast<int>(face.size());
    stream.push_back(n);
    for (int k = 0; k < n; ++k)
    {
      stream.push_back(mid(face[k], face[(k + 1) % n]));
    }
    ++nfaces;
  }
  for (int v = 0; v < cell.Corners; ++v)
  {
    int around[4];
    int valence = 0;
    for (const std::array<int, 2>& e : cell.Edges)
    {
      if ((e[0] == v || e[1] == v) && valence < 4)
      {
        around[valence++] = e[0] == v ? e[1] : e[0];
      }
    }
    if (valence == 4)
    {
      // The pyramid's apex: its edges' mid nodes in the base's order make a
      // pyramid like the cell; their loop faces the apex, outward of the rest.
      stream.push_back(4);
      for (int k = 0; k < 4; ++k)
      {
        pyramids.push_back(mid(v, around[k]));
        stream.push_back(mid(v, around[k]));
      }
      pyramids.push_back(nodes[v]);
      ++nfaces;
      continue;
    }
    // A face through v, outward (..., p, v, q, ...): then (v, p, q, r) is
    // positive, r the third neighbour.
    int p = -1, q = -1;
    for (const std::vector<int>& face : cell.Faces)
    {
      const int n = static_cast<int>(face.size());
      for (int k = 0; k < n && p < 0; ++k)
      {
        if (face[k] == v)
        {
          p = face[(k + n - 1) % n];
          q = face[(k + 1) % n];
        }
      }
    }
    int r = -1;
    for (int k = 0; k < valence; ++k)
    {
      r = (around[k] != p && around[k] != q) ? around[k] : r;
    }
    tetrahedra.insert(tetrahedra.end(), { nodes[v], mid(v, p), mid(v, q), mid(v, r) });
    // The cut is the tetrahedron's face away from v, outward of the
    // tetrahedron: reversed, outward of the rest.
    stream.insert(stream.end(), { 3, mid(v, p), mid(v, r), mid(v, q) });
    ++nfaces;
  }
  return nfaces;
}

/// The tetrahedra of one standard linear cell (CellSplit), appended.
SplitStatus SplitLinear(CellShape shape, const double* points, const Index* corners,
  std::vector<Index>& tetrahedra, const Index* keys)
{
  thread_local std::vector<Index> stream;
  const int nfaces = StandardCellFaces(shape, corners, stream);
  return SplitPolyhedron(points, stream.data(), nfaces, true, tetrahedra, keys);
}

SplitStatus SplitCornerCut(NodalType type, const double* points, const Index* nodes,
  std::vector<Index>& tetrahedra, const Index* keys)
{
  thread_local std::vector<Index> corners;
  thread_local std::vector<Index> pyramids;
  thread_local std::vector<Index> stream;
  corners.clear();
  pyramids.clear();
  stream.clear();
  const int nfaces = CutCorners(CornerCutTable(type), nodes, corners, pyramids, stream);
  const size_t first = tetrahedra.size();
  tetrahedra.insert(tetrahedra.end(), corners.begin(), corners.end());
  for (size_t k = 0; k < pyramids.size(); k += 5)
  {
    const SplitStatus s = SplitLinear(CellShape::Pyramid, points, &pyramids[k], tetrahedra, keys);
    if (s != SplitStatus::Split)
    {
      tetrahedra.resize(first);
      return s;
    }
  }
  const SplitStatus s = SplitPolyhedron(points, stream.data(), nfaces, true, tetrahedra, keys);
  if (s != SplitStatus::Split)
  {
    tetrahedra.resize(first);
  }
  return s;
}

/// Hexa27's nodes on its 3x3x3 lattice: (2x, 2y, 2z) of each node's
/// parametric coordinates (vtkTriQuadraticHexahedron::GetParametricCoords).
const int Hexa27Lattice[27][3] = { { 0, 0, 0 }, { 2, 0, 0 }, { 2, 2, 0 }, { 0, 2, 0 }, { 0, 0, 2 },
  { 2, 0, 2 }, { 2, 2, 2 }, { 0, 2, 2 }, { 1, 0, 0 }, { 2, 1, 0 }, { 1, 2, 0 }, { 0, 1, 0 },
  { 1, 0, 2 }, { 2, 1, 2 }, { 1, 2, 2 }, { 0, 1, 2 }, { 0, 0, 1 }, { 2, 0, 1 }, { 2, 2, 1 },
  { 0, 2, 1 }, { 0, 1, 1 }, { 2, 1, 1 }, { 1, 0, 1 }, { 1, 2, 1 }, { 1, 1, 0 }, { 1, 1, 2 },
  { 1, 1, 1 } };

/// Wedge18's nodes: (2r, 2s, 2t) of its parametric coordinates
/// (vtkBiQuadraticQuadraticWedge::GetParametricCoords).
const int Wedge18Lattice[18][3] = { { 0, 0, 0 }, { 2, 0, 0 }, { 0, 2, 0 }, { 0, 0, 2 }, { 2, 0, 2 },
  { 0, 2, 2 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 1, 0, 2 }, { 1, 1, 2 }, { 0, 1, 2 },
  { 0, 0, 1 }, { 2, 0, 1 }, { 0, 2, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };

/// The node at lattice point (i, j, k) of a lattice table, or -1.
template <int N>
int LatticeNode(const int (&lattice)[N][3], int i, int j, int k)
{
  for (int n = 0; n < N; ++n)
  {
    if (lattice[n][0] == i && lattice[n][1] == j && lattice[n][2] == k)
    {
      return n;
    }
  }
  return -1;
}

SplitStatus SplitSubCells(NodalType type, const double* points, const Index* nodes,
  std::vector<Index>& tetrahedra, const Index* keys)
{
  const size_t first = tetrahedra.size();
  Index corners[8];
  auto split = [&](CellShape shape) {
    const SplitStatus s = SplitLinear(shape, points, corners, tetrahedra, keys);
    if (s != SplitStatus::Split)
    {
      tetrahedra.resize(first);
    }
    return s;
  };
  if (type == NodalType::Hexa27)
  {
    for (int k = 0; k < 2; ++k)
    {
      for (int j = 0; j < 2; ++j)
      {
        for (int i = 0; i < 2; ++i)
        {
          static const int cube[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 },
            { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
          for (int c = 0; c < 8; ++c)
          {
            corners[c] =
              nodes[LatticeNode(Hexa27Lattice, i + cube[c][0], j + cube[c][1], k + cube[c][2])];
          }
          const SplitStatus s = split(CellShape::Hexahedron);
          if (s != SplitStatus::Split)
          {
            return s;
          }
        }
      }
    }
    return SplitStatus::Split;
  }
  // Wedge18: the 6-node triangle's 4 sub-triangles (in (2r, 2s)) on 2
  // layers, each sub-wedge given upper triangle first (CellSplit's wedge
  // table, read with VTK's parametric orientation, is then outward).
  static const int triangles[4][3][2] = { { { 0, 0 }, { 1, 0 }, { 0, 1 } },
    { { 1, 0 }, { 2, 0 }, { 1, 1 } }, { { 0, 1 }, { 1, 1 }, { 0, 2 } },
    { { 1, 0 }, { 1, 1 }, { 0, 1 } } };
  for (int layer = 0; layer < 2; ++layer)
  {
    for (const auto& t : triangles)
    {
      for (int c = 0; c < 6; ++c)
      {
        corners[c] =
          nodes[LatticeNode(Wedge18Lattice, t[c % 3][0], t[c % 3][1], layer + 1 - c / 3)];
      }
      const SplitStatus s = split(CellShape::Wedge);
      if (s != SplitStatus::Split)
      {
        return s;
      }
    }
  }
  return SplitStatus::Split;
}

/// 3D: the tetrahedra from `first` on, flat ones left out; false (nothing
/// kept) when two of them have opposite orientations (a folded cell).
bool KeepOneSigned(const double* points, std::vector<Index>& tetrahedra, size_t first, double size)
{
  const double flat = 1e-12 * size * size * size;
  int sign = 0;
  size_t kept = first;
  for (size_t t = first; t < tetrahedra.size(); t += 4)
  {
    const Index* v = &tetrahedra[t];
    const double six =
      Orient3D(points + 3 * v[0], points + 3 * v[1], points + 3 * v[2], points + 3 * v[3]);
    if (std::fabs(six) <= flat)
    {
      continue;
    }
    const int s = six > 0 ? 1 : -1;
    if (sign != 0 && s != sign)
    {
      tetrahedra.resize(first);
      return false;
    }
    sign = s;
    std::copy(v, v + 4, tetrahedra.begin() + static_cast<std::ptrdiff_t>(kept));
    kept += 4;
  }
  tetrahedra.resize(kept);
  return true;
}

void Cross(const double* a, const double* b, const double* c, double* n)
{
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
}

/// 2D: the triangles from `first` on, against the (Newell) normal of the
/// cell's outline `loop`: those of (nearly) no area left out; false
/// (nothing kept) when one faces the other way (a folded cell).
bool KeepFacingOutline(const double* points, const Index* loop, int n,
  std::vector<Index>& triangles, size_t first, double size)
{
  double normal[3] = { 0, 0, 0 };
  for (int k = 0; k < n; ++k)
  {
    const double* a = points + 3 * loop[k];
    const double* b = points + 3 * loop[(k + 1) % n];
    normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
    normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
    normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  const double length =
    std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  const double flat = 1e-12 * size * size;
  size_t kept = first;
  for (size_t t = first; t < triangles.size(); t += 3)
  {
    const Index* v = &triangles[t];
    double m[3];
    Cross(points + 3 * v[0], points + 3 * v[1], points + 3 * v[2], m);
    const double along =
      (m[0] * normal[0] + m[1] * normal[1] + m[2] * normal[2]) / (length > 0.0 ? length : 1.0);
    if (std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]) <= flat)
    {
      continue;
    }
    if (!(along > 0.0))
    {
      triangles.resize(first);
      return false;
    }
    std::copy(v, v + 3, triangles.begin() + static_cast<std::ptrdiff_t>(kept));
    kept += 3;
  }
  triangles.resize(kept);
  return true;
}

SplitStatus SplitSurfaceCell(NodalType type, const double* points, const Index* nodes,
  std::vector<Index>& triangles, const Index* keys)
{
  const size_t first = triangles.size();
  auto polygon = [&](std::initializer_list<int> local) {
    Index ids[4];
    int n = 0;
    for (int k : local)
    {
      ids[n++] = nodes[k];
    }
    return SplitPolygon(points, ids, n, triangles, keys);
  };
  auto triangle = [&](int a, int b, int c) {
    triangles.insert(triangles.end(), { nodes[a], nodes[b], nodes[c] });
  };
  bool simple = true;
  Index outline[8];
  int n = 0;
  if (type == NodalType::Triangle6)
  {
    triangle(0, 3, 5);
    triangle(3, 1, 4);
    triangle(5, 4, 2);
    triangle(3, 4, 5);
    for (int k : { 0, 3, 1, 4, 2, 5 })
    {
      outline[n++] = nodes[k];
    }
  }
  else
  {
    if (type == NodalType::Quad8)
    {
      triangle(0, 4, 7);
      triangle(4, 1, 5);
      triangle(5, 2, 6);
      triangle(7, 6, 3);
      simple = polygon({ 4, 5, 6, 7 });
    }
    else // Quad9: the 4 quadrilaterals about the centre
    {
      simple = polygon({ 0, 4, 8, 7 }) && polygon({ 4, 1, 5, 8 }) && polygon({ 8, 5, 2, 6 }) &&
        polygon({ 7, 8, 6, 3 });
    }
    for (int k : { 0, 4, 1, 5, 2, 6, 3, 7 })
    {
      outline[n++] = nodes[k];
    }
  }
  if (!simple)
  {
    triangles.resize(first);
    return SplitStatus::NotStarShaped;
  }
  return KeepFacingOutline(
           points, outline, n, triangles, first, Size(points, nodes, NodalNodeCount(type)))
    ? SplitStatus::Split
    : SplitStatus::NotStarShaped;
}

SplitStatus SplitEdge(const double* points, const Index* nodes, std::vector<Index>& segments)
{
  // The mid node between the ends along the chord, else the two segments
  // overlap (the curve folds back).
  const double* a = points + 3 * nodes[0];
  const double* b = points + 3 * nodes[1];
  const double* m = points + 3 * nodes[2];
  double before = 0.0, after = 0.0;
  for (int d = 0; d < 3; ++d)
  {
    before += (m[d] - a[d]) * (b[d] - a[d]);
    after += (b[d] - m[d]) * (b[d] - a[d]);
  }
  if (!(before > 0.0 && after > 0.0))
  {
    return SplitStatus::NotStarShaped;
  }
  segments.insert(segments.end(), { nodes[0], nodes[2], nodes[2], nodes[1] });
  return SplitStatus::Split;
}
} // namespace

SplitStatus SplitNodalCell(NodalType type, const double* points, const Index* nodes,
  std::vector<Index>& simplices, const Index* keys)
{
  switch (type)
  {
    case NodalType::None:
      return SplitStatus::Split;
    case NodalType::Edge3:
      return SplitEdge(points, nodes, simplices);
    case NodalType::Triangle6:
    case NodalType::Quad8:
    case NodalType::Quad9:
      return SplitSurfaceCell(type, points, nodes, simplices, keys);
    default:
      break;
  }
  const size_t first = simplices.size();
  const SplitStatus s = (type == NodalType::Hexa27 || type == NodalType::Wedge18)
    ? SplitSubCells(type, points, nodes, simplices, keys)
    : SplitCornerCut(type, points, nodes, simplices, keys);
  if (s != SplitStatus::Split)
  {
    return s;
  }
  return KeepOneSigned(points, simplices, first, Size(points, nodes, NodalNodeCount(type)))
    ? SplitStatus::Split
    : SplitStatus::NotStarShaped;
}
} // namespace mp
