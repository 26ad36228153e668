// SPDX-License-Identifier: BSD-3-Clause
// Generated meshes for the kernel tests and the benchmark (no VTK): jittered grids with random
// diagonals (optionally with quads cut out, for non-convex and holed
// domains), uniform refinement, rigid motions. No VTK.
#ifndef MeshProjection_Testing_GeneratedMeshes_h
#define MeshProjection_Testing_GeneratedMeshes_h

#include "Geometry/TriangleIntersector.h"
#include "Mesh/CellNeighbors.h"
#include "Mesh/MeshView.h"
#include "Search/CandidateLocator.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace mptest
{
using mp::Index;

struct TestMesh
{
  int Dimension = 2;          // 2: triangles, 3: tetrahedra
  bool Surface = false;       // triangles of a surface, or a curve, in 3D (SpaceDimension 3)
  std::vector<double> Points; // x, y, z
  std::vector<Index> Cells;   // Dimension + 1 per cell
  std::vector<mp::NeighborId> Neighbors;

  Index NumberOfPoints() const { return Index(this->Points.size() / 3); }
  Index NumberOfCells() const { return Index(this->Cells.size() / (this->Dimension + 1)); }
  void Finish() { mp::BuildFaceNeighbors(this->View(false), this->Neighbors); }
  mp::MeshView View(bool withNeighbors = true) const
  {
    mp::MeshView v;
    v.CellDimension = this->Dimension;
    v.SpaceDimension = this->Surface ? 3 : std::max(2, this->Dimension); // curves: in the plane
    v.Points = this->Points.data();
    v.NumberOfPoints = this->NumberOfPoints();
    v.Connectivity = this->Cells.data();
    v.NumberOfCells = this->NumberOfCells();
    v.Neighbors = withNeighbors ? this->Neighbors.data() : nullptr;
    return v;
  }
  double CellArea(Index c) const
  {
    if (this->Dimension == 3)
    {
      return this->CellVolume(c);
    }
    const double* a = &this->Points[3 * this->Cells[3 * c]];
    const double* b = &this->Points[3 * this->Cells[3 * c + 1]];
    const double* d = &this->Points[3 * this->Cells[3 * c + 2]];
    return 0.5 * std::fabs((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]));
  }
  double CellVolume(Index c) const
  {
    const Index* ids = &this->Cells[4 * c];
    const double* a = &this->Points[3 * ids[0]];
    double e[3][3];
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d)
        e[k][d] = this->Points[3 * ids[k + 1] + d] - a[d];
    return std::fabs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
             e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
             e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
      6.0;
  }
  /// Area (2D) or volume (3D) of the mesh.
  double Area() const
  {
    double sum = 0;
    for (Index c = 0; c < this->NumberOfCells(); ++c)
    {
      sum += this->CellArea(c);
    }
    return sum;
  }
  /// Exact integral of a P1 field (one value per point).
  double Integral(const std::vector<double>& u) const
  {
    const int n = this->Dimension + 1;
    double sum = 0;
    for (Index c = 0; c < this->NumberOfCells(); ++c)
    {
      double mean = 0;
      for (int k = 0; k < n; ++k)
        mean += u[this->Cells[n * c + k]] / n;
      sum += this->CellArea(c) * mean;
    }
    return sum;
  }
};

/**
 * A grid of nx x ny quads over [x0,x1]x[y0,y1], each split along a random
 * diagonal. `keep(cx, cy)` (quad centre) cuts quads out. Points strictly
 * inside the kept region move by up to `jitter` times the spacing; boundary
 * points stay, so the domain is exactly the union of the kept quads.
 */
inline TestMesh GridMesh(int nx, int ny, double jitter, unsigned seed, double x0 = 0, double y0 = 0,
  double x1 = 1, double y1 = 1, const std::function<bool(double, double)>& keep = nullptr)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double hx = (x1 - x0) / nx;
  const double hy = (y1 - y0) / ny;
  auto kept = [&](int i, int j) {
    return i >= 0 && j >= 0 && i < nx && j < ny &&
      (!keep || keep(x0 + (i + 0.5) * hx, y0 + (j + 0.5) * hy));
  };
  TestMesh m;
  std::vector<Index> id((nx + 1) * (ny + 1), -1);
  auto point = [&](int i, int j) -> Index {
    Index& p = id[j * (nx + 1) + i];
    if (p < 0)
    {
      double x = (i == nx) ? x1 : x0 + i * hx;
      double y = (j == ny) ? y1 : y0 + j * hy;
      if (kept(i - 1, j - 1) && kept(i, j - 1) && kept(i - 1, j) && kept(i, j))
      {
        x += jitter * hx * unit(rng);
        y += jitter * hy * unit(rng);
      }
      p = m.NumberOfPoints();
      m.Points.insert(m.Points.end(), { x, y, 0.0 });
    }
    return p;
  };
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      if (!kept(i, j))
      {
        continue;
      }
      const Index a = point(i, j);
      const Index b = point(i + 1, j);
      const Index c = point(i + 1, j + 1);
      const Index d = point(i, j + 1);
      if (rng() & 1u)
      {
        m.Cells.insert(m.Cells.end(), { a, b, c, a, c, d });
      }
      else
      {
        m.Cells.insert(m.Cells.end(), { a, b, d, b, c, d });
      }
    }
  }
  for (Index c = 0; c < m.NumberOfCells(); ++c)
  {
    const double* a = &m.Points[3 * m.Cells[3 * c]];
    const double* b = &m.Points[3 * m.Cells[3 * c + 1]];
    const double* d = &m.Points[3 * m.Cells[3 * c + 2]];
    if ((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]) <= 0)
    {
      throw std::runtime_error("GridMesh: jitter too large, a triangle is inverted");
    }
  }
  m.Finish();
  return m;
}

/// Splits every triangle into four through its edge midpoints.
inline TestMesh Refine(const TestMesh& in)
{
  TestMesh m;
  m.Points = in.Points;
  std::map<std::pair<Index, Index>, Index> mid;
  auto midpoint = [&](Index a, Index b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto it = mid.find(key);
    if (it != mid.end())
    {
      return it->second;
    }
    const Index p = m.NumberOfPoints();
    for (int d = 0; d < 3; ++d)
    {
      m.Points.push_back(0.5 * (in.Points[3 * a + d] + in.Points[3 * b + d]));
    }
    mid[key] = p;
    return p;
  };
  for (Index c = 0; c < in.NumberOfCells(); ++c)
  {
    const Index a = in.Cells[3 * c];
    const Index b = in.Cells[3 * c + 1];
    const Index d = in.Cells[3 * c + 2];
    const Index ab = midpoint(a, b);
    const Index bd = midpoint(b, d);
    const Index da = midpoint(d, a);
    m.Cells.insert(m.Cells.end(), { a, ab, da, ab, b, bd, da, bd, d, ab, bd, da });
  }
  m.Finish();
  return m;
}

/**
 * The box [0,1]^3 (scaled by `size`) as nx x ny x nz cubes, each cut into the
 * six Kuhn tetrahedra around its main diagonal (a conforming mesh). Points
 * strictly inside move by up to `jitter` times the spacing.
 */
inline TestMesh CubeMesh(int nx, int ny, int nz, double jitter, unsigned seed, double size = 1.0)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  TestMesh m;
  m.Dimension = 3;
  const int n[3] = { nx, ny, nz };
  auto id = [&](int i, int j, int k) { return Index((k * (ny + 1) + j) * (nx + 1) + i); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
      {
        const int ijk[3] = { i, j, k };
        bool interior = true;
        double x[3];
        for (int d = 0; d < 3; ++d)
        {
          interior = interior && ijk[d] > 0 && ijk[d] < n[d];
          x[d] = size * ijk[d] / n[d];
        }
        for (int d = 0; d < 3 && interior; ++d)
          x[d] += jitter * size / n[d] * unit(rng);
        m.Points.insert(m.Points.end(), { x[0], x[1], x[2] });
      }
  const int perms[6][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 },
    { 2, 1, 0 } };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& p : perms)
        {
          int c[3] = { i, j, k };
          m.Cells.push_back(id(c[0], c[1], c[2]));
          for (int step = 0; step < 3; ++step)
          {
            ++c[p[step]];
            m.Cells.push_back(id(c[0], c[1], c[2]));
          }
        }
  for (Index c = 0; c < m.NumberOfCells(); ++c)
  {
    if (!(m.CellVolume(c) > 1e-6 * size * size * size / (nx * ny * nz)))
    {
      throw std::runtime_error("CubeMesh: jitter too large, a tetrahedron collapsed");
    }
  }
  m.Finish();
  return m;
}

/// A polyline through the points x(s) for s in `params` (closed: back to the first).
inline TestMesh Polyline(const std::vector<double>& params,
  const std::function<void(double, double*)>& x, bool closed, int space = 2)
{
  TestMesh m;
  m.Dimension = 1;
  m.Surface = space == 3; // the view's SpaceDimension: 3 for curves in space
  for (double s : params)
  {
    double p[3] = { 0, 0, 0 };
    x(s, p);
    m.Points.insert(m.Points.end(), p, p + 3);
  }
  const Index n = static_cast<Index>(params.size());
  for (Index i = 0; i + 1 < n + (closed ? 1 : 0); ++i)
  {
    m.Cells.insert(m.Cells.end(), { i, (i + 1) % n });
  }
  m.Finish();
  return m;
}

/// n + 1 (closed: n) parameters from `from` to `to`, inner ones jittered by up to `jitter` steps.
inline std::vector<double> Uniform(
  int n, double from, double to, double jitter, unsigned seed, bool closed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> d(-jitter, jitter);
  std::vector<double> s;
  const int count = closed ? n : n + 1;
  const double h = (to - from) / n;
  for (int i = 0; i < count; ++i)
  {
    const bool end = !closed && (i == 0 || i == n);
    s.push_back(from + h * (i + (end ? 0.0 : d(random))));
  }
  return s;
}

/// Rotates about the z axis by `angle`, then about the x axis by `tilt`,
/// scales and translates (by tx, ty, tz).
inline void Move3D(
  TestMesh& m, double angle, double tilt, double scale, double tx, double ty, double tz)
{
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const double ct = std::cos(tilt);
  const double st = std::sin(tilt);
  for (Index p = 0; p < m.NumberOfPoints(); ++p)
  {
    double* x = &m.Points[3 * p];
    const double a = c * x[0] - s * x[1];
    const double b = s * x[0] + c * x[1];
    const double z = x[2];
    x[0] = scale * a + tx;
    x[1] = scale * (ct * b - st * z) + ty;
    x[2] = scale * (st * b + ct * z) + tz;
  }
}

/// Rotates by `angle` about the origin, scales, then translates.
inline void Move(TestMesh& m, double angle, double scale, double tx, double ty)
{
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  for (Index p = 0; p < m.NumberOfPoints(); ++p)
  {
    const double x = m.Points[3 * p];
    const double y = m.Points[3 * p + 1];
    m.Points[3 * p] = scale * (c * x - s * y) + tx;
    m.Points[3 * p + 1] = scale * (s * x + c * y) + ty;
  }
}

/// Values of f at the points of a mesh.
inline std::vector<double> Sample(const TestMesh& m, const std::function<double(double, double)>& f)
{
  std::vector<double> u(static_cast<size_t>(m.NumberOfPoints()));
  for (Index p = 0; p < m.NumberOfPoints(); ++p)
  {
    u[p] = f(m.Points[3 * p], m.Points[3 * p + 1]);
  }
  return u;
}

inline std::vector<double> Sample3D(
  const TestMesh& m, const std::function<double(double, double, double)>& f)
{
  std::vector<double> u(static_cast<size_t>(m.NumberOfPoints()));
  for (Index p = 0; p < m.NumberOfPoints(); ++p)
  {
    u[p] = f(m.Points[3 * p], m.Points[3 * p + 1], m.Points[3 * p + 2]);
  }
  return u;
}
/// The triangle (0,0),(1,0),(0,1) alone; its source split at the midpoint
/// m = (1/2,1/2) of its hypotenuse: S0 = (0,(1,0),m), S1 = (0,m,(0,1)).
/// Source points: 0 (0,0), 1 (1,0), 2 (0,1), 3 m.
/// Appends `other`'s points and cells to `m` (a mesh of several pieces).
inline void AppendMesh(TestMesh& m, const TestMesh& other)
{
  const Index shift = m.NumberOfPoints();
  m.Points.insert(m.Points.end(), other.Points.begin(), other.Points.end());
  for (Index id : other.Cells)
  {
    m.Cells.push_back(id + shift);
  }
}

/**
 * The sphere of `radius` about the origin, facetized from an icosahedron
 * whose faces are split into `n` x `n` triangles, projected radially:
 * 20 n^2 triangles, counterclockwise seen from outside (from inside when
 * `inward`). Points shared by faces are merged.
 */
inline TestMesh Icosphere(int n, double radius = 1.0, bool inward = false)
{
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  const double v[12][3] = { { -1, g, 0 }, { 1, g, 0 }, { -1, -g, 0 }, { 1, -g, 0 }, { 0, -1, g },
    { 0, 1, g }, { 0, -1, -g }, { 0, 1, -g }, { g, 0, -1 }, { g, 0, 1 }, { -g, 0, -1 },
    { -g, 0, 1 } };
  const int f[20][3] = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 },
    { 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 }, { 3, 9, 4 }, { 3, 4, 2 },
    { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 }, { 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 },
    { 9, 8, 1 } };
  TestMesh m;
  m.Dimension = 2;
  m.Surface = true;
  // Points keyed by their lattice position on an edge or face, so that
  // faces sharing an edge share its points.
  std::map<std::vector<long>, Index> ids;
  auto point = [&](int face, int i, int j) -> Index {
    // Barycentric lattice coordinates (n - i - j, i, j) over the face's corners.
    const int c[3] = { f[face][0], f[face][1], f[face][2] };
    const int w[3] = { n - i - j, i, j };
    std::vector<long> key;
    for (int k = 0; k < 3; ++k)
    {
      if (w[k] > 0)
      {
        key.push_back(c[k]);
        key.push_back(w[k]);
      }
    }
    // Order (corner, weight) pairs by corner: the same key from any face.
    std::vector<std::pair<long, long>> pairs;
    for (size_t k = 0; k < key.size(); k += 2)
    {
      pairs.emplace_back(key[k], key[k + 1]);
    }
    std::sort(pairs.begin(), pairs.end());
    key.clear();
    for (const auto& p : pairs)
    {
      key.push_back(p.first);
      key.push_back(p.second);
    }
    auto found = ids.find(key);
    if (found != ids.end())
    {
      return found->second;
    }
    double x[3] = { 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      for (int d = 0; d < 3; ++d)
      {
        x[d] += v[c[k]][d] * w[k] / double(n);
      }
    }
    const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    const Index id = m.NumberOfPoints();
    for (int d = 0; d < 3; ++d)
    {
      m.Points.push_back(radius * x[d] / r);
    }
    ids.emplace(key, id);
    return id;
  };
  auto add = [&](Index a, Index b, Index c) {
    m.Cells.insert(m.Cells.end(), { a, inward ? c : b, inward ? b : c });
  };
  for (int face = 0; face < 20; ++face)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i + j < n; ++i)
      {
        add(point(face, i, j), point(face, i + 1, j), point(face, i, j + 1));
        if (i + j + 1 < n)
        {
          add(point(face, i + 1, j), point(face, i + 1, j + 1), point(face, i, j + 1));
        }
      }
    }
  }
  return m;
}

/**
 * The sphere of `radius` about the origin as latitude-longitude facets:
 * `rings` bands, `sectors` around, the polar bands as fans, the others as
 * quads split along alternating diagonals; counterclockwise seen from outside.
 */
inline TestMesh UvSphere(int rings, int sectors, double radius = 1.0)
{
  const double pi = 3.14159265358979323846;
  TestMesh m;
  m.Dimension = 2;
  m.Surface = true;
  m.Points.insert(m.Points.end(), { 0.0, 0.0, radius });
  for (int r = 1; r < rings; ++r)
  {
    const double theta = pi * r / rings;
    for (int k = 0; k < sectors; ++k)
    {
      const double phi = 2.0 * pi * (k + 0.37 * r) / sectors; // each ring turned by 0.37 sector
      m.Points.insert(m.Points.end(),
        { radius * std::sin(theta) * std::cos(phi), radius * std::sin(theta) * std::sin(phi),
          radius * std::cos(theta) });
    }
  }
  m.Points.insert(m.Points.end(), { 0.0, 0.0, -radius });
  const Index south = m.NumberOfPoints() - 1;
  auto ring = [&](int r, int k) -> Index { return 1 + (r - 1) * sectors + (k % sectors); };
  for (int k = 0; k < sectors; ++k)
  {
    m.Cells.insert(m.Cells.end(), { 0, ring(1, k), ring(1, k + 1) });
    m.Cells.insert(m.Cells.end(), { south, ring(rings - 1, k + 1), ring(rings - 1, k) });
  }
  for (int r = 1; r + 1 < rings; ++r)
  {
    for (int k = 0; k < sectors; ++k)
    {
      const Index a = ring(r, k), b = ring(r + 1, k), c = ring(r + 1, k + 1), d = ring(r, k + 1);
      if ((r + k) % 2)
      {
        m.Cells.insert(m.Cells.end(), { a, b, c, a, c, d });
      }
      else
      {
        m.Cells.insert(m.Cells.end(), { a, b, d, b, c, d });
      }
    }
  }
  return m;
}

/**
 * The surface of the cube [0, 1]^3: each face an n x n grid of squares,
 * split along one diagonal (`diagonal` 0) or the other (1), outward normals.
 * Points on the edges and corners are shared between faces.
 */
inline TestMesh CubeSurface(int n, int diagonal)
{
  TestMesh m;
  m.Dimension = 2;
  m.Surface = true;
  std::map<std::vector<long>, Index> ids;
  auto point = [&](const long(&q)[3]) -> Index {
    const std::vector<long> key(q, q + 3);
    auto found = ids.find(key);
    if (found != ids.end())
    {
      return found->second;
    }
    const Index id = m.NumberOfPoints();
    for (int d = 0; d < 3; ++d)
    {
      m.Points.push_back(double(q[d]) / n);
    }
    ids.emplace(key, id);
    return id;
  };
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int side = 0; side < 2; ++side)
    {
      // (u, v, normal) axes with u x v = +axis; swap for the side at 0.
      int u = (axis + 1) % 3;
      int v = (axis + 2) % 3;
      if (side == 0)
      {
        std::swap(u, v);
      }
      for (int i = 0; i < n; ++i)
      {
        for (int j = 0; j < n; ++j)
        {
          Index c[4];
          const int di[4] = { 0, 1, 1, 0 };
          const int dj[4] = { 0, 0, 1, 1 };
          for (int k = 0; k < 4; ++k)
          {
            long q[3];
            q[axis] = side * n;
            q[u] = i + di[k];
            q[v] = j + dj[k];
            c[k] = point(q);
          }
          if (diagonal == 0)
          {
            m.Cells.insert(m.Cells.end(), { c[0], c[1], c[2], c[0], c[2], c[3] });
          }
          else
          {
            m.Cells.insert(m.Cells.end(), { c[0], c[1], c[3], c[1], c[2], c[3] });
          }
        }
      }
    }
  }
  return m;
}

inline std::pair<TestMesh, TestMesh> SplitTriangle()
{
  TestMesh target;
  target.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  target.Cells = { 0, 1, 2 };
  target.Finish();
  TestMesh source;
  source.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5, 0.5, 0 };
  source.Cells = { 0, 1, 3, 0, 3, 2 };
  source.Finish();
  return { target, source };
}

} // namespace mptest

#endif
