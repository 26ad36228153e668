// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/CellSplit.h"

#include "Geometry/Predicates.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace mp
{
namespace
{
int Sign(double x)
{
  return (x > 0.0) - (x < 0.0);
}

/// The polygon's corners in 2D: the two coordinates left when the one
/// closest to its (Newell) normal is dropped. Orientations keep one sign
/// convention within the polygon, which is all the split compares.
void PlaneCoordinates(const double* points, const Index* ids, int n, std::vector<double>& uv)
{
  double normal[3] = { 0, 0, 0 };
  for (int k = 0; k < n; ++k)
  {
    const double* a = points + 3 * ids[k];
    const double* b = points + 3 * ids[(k + 1) % n];
    normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
    normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
    normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  int drop = 2;
  for (int d = 0; d < 2; ++d)
  {
    drop = std::fabs(normal[d]) > std::fabs(normal[drop]) ? d : drop;
  }
  const int u = drop == 0 ? 1 : 0;
  const int v = drop == 2 ? 1 : 2;
  uv.resize(2 * static_cast<size_t>(n));
  for (int k = 0; k < n; ++k)
  {
    uv[2 * k] = points[3 * ids[k] + u];
    uv[2 * k + 1] = points[3 * ids[k] + v];
  }
}

/// Ear clipping of a simple polygon in 2D (corners 0..n-1 of uv).
bool CutEars(const std::vector<double>& uv, const Index* ids, int n, std::vector<Index>& triangles)
{
  double twiceArea = 0.0;
  for (int k = 0; k < n; ++k)
  {
    const int l = (k + 1) % n;
    twiceArea += uv[2 * k] * uv[2 * l + 1] - uv[2 * l] * uv[2 * k + 1];
  }
  const int s = Sign(twiceArea);
  if (s == 0)
  {
    return false;
  }
  std::vector<int> loop(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k)
  {
    loop[k] = k;
  }
  const size_t start = triangles.size();
  auto at = [&uv](int k) { return &uv[2 * k]; };
  while (loop.size() > 3)
  {
    const int m = static_cast<int>(loop.size());
    bool cut = false;
    for (int i = 0; i < m && !cut; ++i)
    {
      const int a = loop[(i + m - 1) % m];
      const int b = loop[i];
      const int c = loop[(i + 1) % m];
      const int o = Sign(Orient2D(at(a), at(b), at(c)));
      if (o == 0) // b lies on the line a-c: it bounds no area
      {
        loop.erase(loop.begin() + i);
        cut = true;
        break;
      }
      if (o != s)
      {
        continue; // a reflex corner
      }
      bool empty = true;
      for (int j = 0; j < m && empty; ++j)
      {
        const int p = loop[j];
        if (p == a || p == b || p == c)
        {
          continue;
        }
        empty = !(Sign(Orient2D(at(a), at(b), at(p))) != -s &&
          Sign(Orient2D(at(b), at(c), at(p))) != -s && Sign(Orient2D(at(c), at(a), at(p))) != -s);
      }
      if (empty)
      {
        triangles.insert(triangles.end(), { ids[a], ids[b], ids[c] });
        loop.erase(loop.begin() + i);
        cut = true;
      }
    }
    if (!cut)
    {
      triangles.resize(start);
      return false;
    }
  }
  if (Sign(Orient2D(at(loop[0]), at(loop[1]), at(loop[2]))) != 0)
  {
    triangles.insert(triangles.end(), { ids[loop[0]], ids[loop[1]], ids[loop[2]] });
  }
  return true;
}
} // namespace

bool SplitPolygon(
  const double* points, const Index* ids, int n, std::vector<Index>& triangles, const Index* keys)
{
  if (n < 3)
  {
    return true;
  }
  if (n == 3)
  {
    triangles.insert(triangles.end(), { ids[0], ids[1], ids[2] });
    return true;
  }
  thread_local std::vector<double> uv;
  PlaneCoordinates(points, ids, n, uv);
  // The fan from the lowest-numbered corner, when it is one-signed.
  int m = 0;
  for (int k = 1; k < n; ++k)
  {
    m = (keys ? keys[ids[k]] < keys[ids[m]] : ids[k] < ids[m]) ? k : m;
  }
  int sign = 0;
  bool oneSigned = true;
  for (int k = 1; k + 1 < n && oneSigned; ++k)
  {
    const int b = (m + k) % n;
    const int c = (m + k + 1) % n;
    const int o = Sign(Orient2D(&uv[2 * m], &uv[2 * b], &uv[2 * c]));
    oneSigned = o == 0 || sign == 0 || o == sign;
    sign = o != 0 ? o : sign;
  }
  if (oneSigned)
  {
    for (int k = 1; k + 1 < n; ++k)
    {
      const int b = (m + k) % n;
      const int c = (m + k + 1) % n;
      if (Orient2D(&uv[2 * m], &uv[2 * b], &uv[2 * c]) != 0.0)
      {
        triangles.insert(triangles.end(), { ids[m], ids[b], ids[c] });
      }
    }
    return true;
  }
  return CutEars(uv, ids, n, triangles);
}

namespace
{
/// Orients the faces of `stream` (count, ids, count, ids, ...) alike, in
/// place. False when an edge is not shared by exactly two faces, or the
/// faces cannot be oriented alike.
bool OrientFaces(std::vector<Index>& stream, const std::vector<size_t>& start, int nfaces)
{
  // (low id, high id, face, runs low -> high)
  thread_local std::vector<std::tuple<Index, Index, int, bool>> edges;
  edges.clear();
  for (int f = 0; f < nfaces; ++f)
  {
    const Index* v = &stream[start[f] + 1];
    const int n = static_cast<int>(stream[start[f]]);
    for (int k = 0; k < n; ++k)
    {
      const Index a = v[k];
      const Index b = v[(k + 1) % n];
      edges.emplace_back(std::min(a, b), std::max(a, b), f, a < b);
    }
  }
  std::sort(edges.begin(), edges.end());
  // Each face's neighbours across its edges, and whether the two run the
  // edge the same way (then one of them must be reversed).
  thread_local std::vector<std::tuple<int, int, bool>> links;
  links.clear();
  for (size_t i = 0; i < edges.size();)
  {
    size_t j = i + 1;
    while (j < edges.size() && std::get<0>(edges[j]) == std::get<0>(edges[i]) &&
      std::get<1>(edges[j]) == std::get<1>(edges[i]))
    {
      ++j;
    }
    if (j - i != 2)
    {
      return false;
    }
    const bool same = std::get<3>(edges[i]) == std::get<3>(edges[i + 1]);
    links.emplace_back(std::get<2>(edges[i]), std::get<2>(edges[i + 1]), same);
    links.emplace_back(std::get<2>(edges[i + 1]), std::get<2>(edges[i]), same);
    i = j;
  }
  std::sort(links.begin(), links.end());
  thread_local std::vector<int> flip; // -1: not reached yet
  flip.assign(static_cast<size_t>(nfaces), -1);
  thread_local std::vector<int> queue;
  for (int seed = 0; seed < nfaces; ++seed)
  {
    if (flip[seed] >= 0)
    {
      continue;
    }
    flip[seed] = 0;
    queue.assign(1, seed);
    while (!queue.empty())
    {
      const int f = queue.back();
      queue.pop_back();
      auto range = std::equal_range(links.begin(), links.end(), std::make_tuple(f, -1, false),
        [](const std::tuple<int, int, bool>& x, const std::tuple<int, int, bool>& y) {
          return std::get<0>(x) < std::get<0>(y);
        });
      for (auto it = range.first; it != range.second; ++it)
      {
        const int g = std::get<1>(*it);
        const int want = flip[f] ^ static_cast<int>(std::get<2>(*it));
        if (flip[g] < 0)
        {
          flip[g] = want;
          queue.push_back(g);
        }
        else if (flip[g] != want)
        {
          return false;
        }
      }
    }
  }
  for (int f = 0; f < nfaces; ++f)
  {
    if (flip[f])
    {
      std::reverse(stream.begin() + static_cast<std::ptrdiff_t>(start[f] + 1),
        stream.begin() + static_cast<std::ptrdiff_t>(start[f] + 1 + stream[start[f]]));
    }
  }
  return true;
}
} // namespace

SplitStatus SplitPolyhedron(const double* points, const Index* faces, int nfaces, bool oriented,
  std::vector<Index>& tetrahedra, const Index* keys)
{
  thread_local std::vector<Index> stream;
  thread_local std::vector<size_t> start;
  thread_local std::vector<Index> corners;
  stream.clear();
  start.clear();
  corners.clear();
  const Index* f = faces;
  for (int k = 0; k < nfaces; ++k)
  {
    const Index n = *f;
    if (n < 3)
    {
      return SplitStatus::OpenFaces;
    }
    start.push_back(stream.size());
    stream.insert(stream.end(), f, f + n + 1);
    corners.insert(corners.end(), f + 1, f + n + 1);
    f += n + 1;
  }
  if (!oriented && !OrientFaces(stream, start, nfaces))
  {
    return SplitStatus::OpenFaces;
  }
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  if (keys)
  {
    // Apexes tried in the order of their keys.
    std::sort(
      corners.begin(), corners.end(), [keys](Index a, Index b) { return keys[a] < keys[b]; });
  }
  if (corners.empty())
  {
    return SplitStatus::OpenFaces;
  }
  // Tetrahedra flatter than this (six times the volume, against the cube of
  // the cell's size) are left out whatever their sign: the pieces of a face
  // split into coplanar faces (a refinement interface of an OpenFOAM mesh),
  // or of faces nearly in the apex's plane, whose orientation is rounding.
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = hi[d] = points[3 * corners[0] + d];
  }
  for (Index c : corners)
  {
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min(lo[d], points[3 * c + d]);
      hi[d] = std::max(hi[d], points[3 * c + d]);
    }
  }
  const double size = std::max({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2] });
  const double flat = 1e-12 * size * size * size;
  const size_t first = tetrahedra.size();
  // The cone from a corner over every face's fan (a face's fan is fixed by
  // the face's own lowest corner, so neighbours agree whatever the apex).
  // Faces through the apex give flat tetrahedra when they are planar, and
  // the thin wedge between their two possible fans when they are warped.
  auto cone = [&](Index apex) {
    const double* x = points + 3 * apex;
    int sign = 0;
    for (int k = 0; k < nfaces; ++k)
    {
      const Index* v = &stream[start[k] + 1];
      const int n = static_cast<int>(stream[start[k]]);
      int m = 0;
      for (int i = 1; i < n; ++i)
      {
        m = (keys ? keys[v[i]] < keys[v[m]] : v[i] < v[m]) ? i : m;
      }
      for (int i = 1; i + 1 < n; ++i)
      {
        const Index a = v[m];
        const Index b = v[(m + i) % n];
        const Index c = v[(m + i + 1) % n];
        if (a == apex || b == apex || c == apex)
        {
          continue;
        }
        const double six = Orient3D(x, points + 3 * a, points + 3 * b, points + 3 * c);
        if (std::fabs(six) <= flat)
        {
          continue;
        }
        const int o = Sign(six);
        if (sign != 0 && o != sign)
        {
          tetrahedra.resize(first);
          return false;
        }
        sign = o;
        tetrahedra.insert(tetrahedra.end(), { apex, a, b, c });
      }
    }
    return true;
  };
  // The lowest corner first; a cell that folds from it (non-convex) may be
  // star-shaped from another corner.
  for (Index apex : corners)
  {
    if (cone(apex))
    {
      return SplitStatus::Split;
    }
  }
  return SplitStatus::NotStarShaped;
}

int StandardCellFaces(CellShape shape, const Index* corners, std::vector<Index>& stream)
{
  stream.clear();
  auto face = [&](std::initializer_list<int> local, const int* order) {
    stream.push_back(static_cast<Index>(local.size()));
    for (int k : local)
    {
      stream.push_back(corners[order ? order[k] : k]);
    }
  };
  // Prisms over an n-gon (the hexahedron is the one over a quadrilateral):
  // the bottom reversed, the top, the sides; each edge runs once each way.
  auto prism = [&](int n, const int* order) {
    stream.push_back(n);
    for (int k = 0; k < n; ++k)
    {
      const int local = (n - k) % n;
      stream.push_back(corners[order ? order[local] : local]);
    }
    stream.push_back(n);
    for (int k = 0; k < n; ++k)
    {
      stream.push_back(corners[order ? order[n + k] : n + k]);
    }
    for (int k = 0; k < n; ++k)
    {
      const int l = (k + 1) % n;
      face({ k, l, n + l, n + k }, order);
    }
    return n + 2;
  };
  static const int voxel[8] = { 0, 1, 3, 2, 4, 5, 7, 6 };
  switch (shape)
  {
    case CellShape::Hexahedron:
      return prism(4, nullptr);
    case CellShape::Voxel:
      return prism(4, voxel);
    case CellShape::PentagonalPrism:
      return prism(5, nullptr);
    case CellShape::HexagonalPrism:
      return prism(6, nullptr);
    case CellShape::Wedge:
      face({ 0, 1, 2 }, nullptr);
      face({ 3, 5, 4 }, nullptr);
      face({ 0, 3, 4, 1 }, nullptr);
      face({ 1, 4, 5, 2 }, nullptr);
      face({ 2, 5, 3, 0 }, nullptr);
      return 5;
    case CellShape::Pyramid:
      face({ 0, 3, 2, 1 }, nullptr);
      face({ 0, 1, 4 }, nullptr);
      face({ 1, 2, 4 }, nullptr);
      face({ 2, 3, 4 }, nullptr);
      face({ 3, 0, 4 }, nullptr);
      return 5;
  }
  return 0;
}
} // namespace mp
