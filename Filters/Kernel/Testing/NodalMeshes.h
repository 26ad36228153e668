// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file NodalMeshes.h
 * @brief Second-order meshes for the kernel tests of the cells' own space
 *        (TestNodalSpace.cxx), each with its split on its own nodes: tri6
 *        squares and tet10 cubes with jittered interior corners and
 *        straight edges, tri6 disks whose boundary mid nodes lie on the
 *        circle, planar meshes moved onto a tilted plane (or one inside
 *        the unit cube), edge3 lines.
 */
#ifndef MeshProjection_Kernel_Testing_NodalMeshes_h
#define MeshProjection_Kernel_Testing_NodalMeshes_h

#include "Mesh/CellNeighbors.h"
#include "Mesh/MeshView.h"
#include "Mesh/NodalCells.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <random>
#include <vector>

namespace nodaltest
{
using mp::Index;
using mp::NodalType;

/// A mesh of second-order (or linear) cells with their split on their nodes.
struct NodalMesh
{
  int Dimension = 2;
  int Space = 0;              // SpaceDimension (0: Dimension)
  std::vector<double> Points; // x, y, z
  std::vector<Index> Cells;   // the split's simplices
  std::vector<Index> Parent;
  std::vector<NodalType> Types;
  std::vector<Index> Offsets{ 0 };
  std::vector<Index> Nodes;
  std::vector<mp::NeighborId> Neighbors;
  mp::NodalCells Nodal;
  bool Linear = false; // no Nodal: P1 on the simplices

  Index NumberOfPoints() const { return Index(this->Points.size() / 3); }
  const double* Point(Index p) const { return &this->Points[3 * p]; }

  void Simplex(std::initializer_list<Index> corners)
  {
    this->Cells.insert(this->Cells.end(), corners);
    this->Parent.push_back(Index(this->Types.size()) - 1);
  }
  /// A tri6 (VTK order) split into its 4 triangles on its nodes.
  void Triangle6(const std::array<Index, 6>& n)
  {
    this->Types.push_back(NodalType::Triangle6);
    this->Nodes.insert(this->Nodes.end(), n.begin(), n.end());
    this->Offsets.push_back(Index(this->Nodes.size()));
    this->Simplex({ n[0], n[3], n[5] });
    this->Simplex({ n[3], n[1], n[4] });
    this->Simplex({ n[5], n[4], n[2] });
    this->Simplex({ n[3], n[4], n[5] });
  }
  /// An edge3 (VTK order: ends, then middle) split into its 2 segments.
  void Edge3(const std::array<Index, 3>& n)
  {
    this->Types.push_back(NodalType::Edge3);
    this->Nodes.insert(this->Nodes.end(), n.begin(), n.end());
    this->Offsets.push_back(Index(this->Nodes.size()));
    this->Simplex({ n[0], n[2] });
    this->Simplex({ n[2], n[1] });
  }
  /// A tet10 (VTK order) split into its 4 corner tetrahedra and the 4 of
  /// its octahedron around the diagonal from mid 01 to mid 23.
  void Tetra10(const std::array<Index, 10>& n)
  {
    this->Types.push_back(NodalType::Tetra10);
    this->Nodes.insert(this->Nodes.end(), n.begin(), n.end());
    this->Offsets.push_back(Index(this->Nodes.size()));
    this->Simplex({ n[0], n[4], n[6], n[7] });
    this->Simplex({ n[4], n[1], n[5], n[8] });
    this->Simplex({ n[6], n[5], n[2], n[9] });
    this->Simplex({ n[7], n[8], n[9], n[3] });
    this->Simplex({ n[4], n[9], n[5], n[8] });
    this->Simplex({ n[4], n[9], n[8], n[7] });
    this->Simplex({ n[4], n[9], n[7], n[6] });
    this->Simplex({ n[4], n[9], n[6], n[5] });
  }
  void Finish()
  {
    this->Nodal.Type = this->Types.data();
    this->Nodal.Offsets = this->Offsets.data();
    this->Nodal.Nodes = this->Nodes.data();
    mp::BuildFaceNeighbors(this->View(false), this->Neighbors);
  }
  mp::MeshView View(bool withNeighbors = true) const
  {
    mp::MeshView v;
    v.CellDimension = this->Dimension;
    v.SpaceDimension = this->Space > 0 ? this->Space : this->Dimension;
    v.Points = this->Points.data();
    v.NumberOfPoints = this->NumberOfPoints();
    v.Connectivity = this->Cells.data();
    v.NumberOfCells = Index(this->Cells.size()) / (this->Dimension + 1);
    if (!this->Linear)
    {
      v.Parent = this->Parent.data();
      v.NumberOfParents = Index(this->Types.size());
      v.Nodal = &this->Nodal;
    }
    v.Neighbors = withNeighbors && !this->Neighbors.empty() ? this->Neighbors.data() : nullptr;
    return v;
  }
};

/// The nodes of a grid of (2n + 1)^d points: corners at even indices, mid
/// nodes between them. Corner (i, j, k) in [0, 1]^d, interior ones moved
/// by up to `jitter` of a cell, mid nodes at the middle of their edges.
struct Grid
{
  int N;
  int D;
  int Size() const { return 2 * this->N + 1; }
  Index Id(int i, int j, int k = 0) const
  {
    return i + Index(this->Size()) * (j + Index(this->Size()) * k);
  }
};

/// Puts every mid node (a grid point with an odd index) at the middle of
/// the edge whose ends are the corners one step away in its odd indices.
inline void PlaceMidNodes(const Grid& g, std::vector<double>& points)
{
  const int s = g.Size();
  for (int k = 0; k < (g.D == 3 ? s : 1); ++k)
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < s; ++i)
      {
        const int odd[3] = { i % 2, j % 2, k % 2 };
        if (odd[0] + odd[1] + odd[2] == 0)
          continue;
        const Index a = g.Id(i - odd[0], j - odd[1], k - odd[2]);
        const Index b = g.Id(i + odd[0], j + odd[1], k + odd[2]);
        for (int c = 0; c < 3; ++c)
          points[3 * g.Id(i, j, k) + c] = 0.5 * (points[3 * a + c] + points[3 * b + c]);
      }
}

/// Corner points of the grid over [0, 1]^d, interior ones jittered.
inline std::vector<double> GridCorners(const Grid& g, double jitter, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> shift(-jitter, jitter);
  const int s = g.Size();
  const int ks = g.D == 3 ? s : 1;
  std::vector<double> points(3 * size_t(s) * s * ks, 0.0);
  for (int k = 0; k < ks; k += 2)
    for (int j = 0; j < s; j += 2)
      for (int i = 0; i < s; i += 2)
      {
        const int index[3] = { i, j, k };
        for (int c = 0; c < g.D; ++c)
        {
          const bool interior =
            i > 0 && i < s - 1 && j > 0 && j < s - 1 && (g.D == 2 || (k > 0 && k < s - 1));
          points[3 * g.Id(i, j, k) + c] =
            (index[c] + (interior ? 2.0 * shift(random) : 0.0)) / (s - 1);
        }
      }
  return points;
}

/// Tri6 cells of an n x n grid of squares (each cut along its rising diagonal).
inline void Triangles6(const Grid& g, NodalMesh& mesh)
{
  for (int j = 0; j + 2 < g.Size(); j += 2)
    for (int i = 0; i + 2 < g.Size(); i += 2)
    {
      mesh.Triangle6({ g.Id(i, j), g.Id(i + 2, j), g.Id(i + 2, j + 2), g.Id(i + 1, j),
        g.Id(i + 2, j + 1), g.Id(i + 1, j + 1) });
      mesh.Triangle6({ g.Id(i, j), g.Id(i + 2, j + 2), g.Id(i, j + 2), g.Id(i + 1, j + 1),
        g.Id(i + 1, j + 2), g.Id(i, j + 1) });
    }
}

inline NodalMesh Square(int n, double jitter, unsigned seed)
{
  const Grid g{ n, 2 };
  NodalMesh mesh;
  mesh.Points = GridCorners(g, jitter, seed);
  PlaceMidNodes(g, mesh.Points);
  Triangles6(g, mesh);
  mesh.Finish();
  return mesh;
}

/// Tet10 cells of an n^3 grid of cubes, each in Kuhn's 6 tetrahedra (the
/// corners along a monotone path: conforming across the cubes).
inline NodalMesh Cube(int n, double jitter, unsigned seed)
{
  const Grid g{ n, 3 };
  NodalMesh mesh;
  mesh.Dimension = 3;
  mesh.Points = GridCorners(g, jitter, seed);
  PlaceMidNodes(g, mesh.Points);
  const int orders[6][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 },
    { 2, 1, 0 } };
  for (int k = 0; k + 2 < g.Size(); k += 2)
    for (int j = 0; j + 2 < g.Size(); j += 2)
      for (int i = 0; i + 2 < g.Size(); i += 2)
        for (const auto& order : orders)
        {
          int v[4][3];
          v[0][0] = i, v[0][1] = j, v[0][2] = k;
          for (int s = 1; s < 4; ++s)
          {
            std::copy(v[s - 1], v[s - 1] + 3, v[s]);
            v[s][order[s - 1]] += 2;
          }
          auto id = [&](int a, int b) {
            return g.Id((v[a][0] + v[b][0]) / 2, (v[a][1] + v[b][1]) / 2, (v[a][2] + v[b][2]) / 2);
          };
          mesh.Tetra10({ id(0, 0), id(1, 1), id(2, 2), id(3, 3), id(0, 1), id(1, 2), id(0, 2),
            id(0, 3), id(1, 3), id(2, 3) });
        }
  mesh.Finish();
  return mesh;
}

/// A tri6 disk of radius 1: the square [-1, 1]^2's grid mapped onto it,
/// mid nodes at their edges' middles but on the boundary, on the circle.
inline NodalMesh Disk(int n)
{
  const Grid g{ n, 2 };
  NodalMesh mesh;
  mesh.Points = GridCorners(g, 0.0, 0);
  for (Index p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    double* x = &mesh.Points[3 * p];
    const double u = 2 * x[0] - 1, v = 2 * x[1] - 1;
    x[0] = u * std::sqrt(1 - 0.5 * v * v);
    x[1] = v * std::sqrt(1 - 0.5 * u * u);
  }
  PlaceMidNodes(g, mesh.Points);
  const int s = g.Size();
  for (int j = 0; j < s; ++j)
    for (int i = 0; i < s; ++i)
      if ((i % 2) + (j % 2) == 1 && (i == 0 || i == s - 1 || j == 0 || j == s - 1))
      {
        double* x = &mesh.Points[3 * g.Id(i, j)];
        const double r = std::hypot(x[0], x[1]);
        x[0] /= r;
        x[1] /= r;
      }
  Triangles6(g, mesh);
  mesh.Finish();
  return mesh;
}

/// A linear mesh (P1 on its triangles, no Nodal): the split of Square's.
inline NodalMesh LinearSquare(int n, double jitter, unsigned seed)
{
  NodalMesh mesh = Square(n, jitter, seed);
  mesh.Linear = true;
  return mesh;
}

/// `mesh` (planar, z = 0) moved onto a tilted plane in space (a surface in 3D).
inline NodalMesh Tilted(NodalMesh mesh)
{
  const double e1[3] = { 0.6, 0.0, 0.8 }, e2[3] = { 0.0, 1.0, 0.0 }, o[3] = { 0.3, -0.2, 0.5 };
  for (Index p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    double* x = &mesh.Points[3 * p];
    const double u = x[0], v = x[1];
    for (int a = 0; a < 3; ++a)
      x[a] = o[a] + u * e1[a] + v * e2[a];
  }
  mesh.Space = 3;
  mesh.Finish();
  return mesh;
}

/// Edge3 cells along the segment from `from` to `to` (in the plane: z = 0),
/// n of them, their ends jittered by up to `jitter` of a cell (mid nodes
/// in the middle).
inline NodalMesh Line(int n, unsigned seed, const std::array<double, 2>& from = { 0.1, 0.2 },
  const std::array<double, 2>& to = { 0.7, 1.0 }, double jitter = 0.2)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> shift(-jitter, jitter);
  NodalMesh mesh;
  mesh.Dimension = 1;
  mesh.Space = 2;
  std::vector<double> t(size_t(2 * n + 1));
  for (int i = 0; i <= 2 * n; i += 2)
    t[i] = (i + (i > 0 && i < 2 * n ? 2.0 * shift(random) : 0.0)) / (2 * n);
  for (int i = 1; i < 2 * n; i += 2)
    t[i] = 0.5 * (t[i - 1] + t[i + 1]);
  for (double s : t)
    mesh.Points.insert(
      mesh.Points.end(), { from[0] + (to[0] - from[0]) * s, from[1] + (to[1] - from[1]) * s, 0.0 });
  for (int i = 0; i < 2 * n; i += 2)
    mesh.Edge3({ i, i + 2, i + 1 });
  mesh.Finish();
  return mesh;
}

/// `mesh` (planar, z = 0, in [0, 1]^2) moved onto the plane through
/// (0.1, 0.15, 0.3) spanned by (0.8, 0, 0.4) and (0, 0.7, 0): inside the unit cube.
inline NodalMesh InsideCube(NodalMesh mesh)
{
  for (Index p = 0; p < mesh.NumberOfPoints(); ++p)
  {
    double* x = &mesh.Points[3 * p];
    const double u = x[0], v = x[1];
    x[0] = 0.1 + 0.8 * u;
    x[1] = 0.15 + 0.7 * v;
    x[2] = 0.3 + 0.4 * u;
  }
  mesh.Space = 3;
  mesh.Finish();
  return mesh;
}

} // namespace nodaltest

#endif
