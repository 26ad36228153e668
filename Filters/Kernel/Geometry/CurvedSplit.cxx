// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/CurvedSplit.h"

#include "Geometry/NodalShapes.h"
#include "Geometry/Predicates.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace mp
{
namespace
{
/// The mid node of each edge (a, b) of a refined type, as VTK numbers them.
struct EdgeMid
{
  int A, B, Mid;
};

const std::vector<EdgeMid>& EdgeMids(NodalType type)
{
  static const std::vector<EdgeMid> edge{ { 0, 1, 2 } };
  static const std::vector<EdgeMid> triangle{ { 0, 1, 3 }, { 1, 2, 4 }, { 2, 0, 5 } };
  static const std::vector<EdgeMid> quad{ { 0, 1, 4 }, { 1, 2, 5 }, { 2, 3, 6 }, { 3, 0, 7 } };
  static const std::vector<EdgeMid> tetra{ { 0, 1, 4 }, { 1, 2, 5 }, { 2, 0, 6 }, { 0, 3, 7 },
    { 1, 3, 8 }, { 2, 3, 9 } };
  static const std::vector<EdgeMid> none;
  switch (type)
  {
    case NodalType::Edge3:
      return edge;
    case NodalType::Triangle6:
      return triangle;
    case NodalType::Quad8:
    case NodalType::Quad9:
      return quad;
    case NodalType::Tetra10:
      return tetra;
    default:
      return none;
  }
}

/// The mid node of edge (a, b) of the type (either order).
int MidOf(NodalType type, int a, int b)
{
  for (const EdgeMid& e : EdgeMids(type))
  {
    if ((e.A == a && e.B == b) || (e.A == b && e.B == a))
    {
      return e.Mid;
    }
  }
  return -1;
}

bool IsQuad(NodalType type)
{
  return type == NodalType::Quad8 || type == NodalType::Quad9;
}

/// The quadrilateral's corner at tensor lattice corner (i, j) in {0, n}^2.
int QuadCorner(int i, int j, int n)
{
  return i == 0 ? (j == 0 ? 0 : 3) : (j == 0 ? 1 : 2);
}

double Determinant3(const double (&m)[3][3])
{
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
    m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
    m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}
} // namespace

bool IsRefinedWhenCurved(NodalType type)
{
  return type == NodalType::Edge3 || type == NodalType::Triangle6 || type == NodalType::Tetra10 ||
    IsQuad(type);
}

double RelativeCurvedSag(NodalType type, const double* points, const Index* nodes, int level)
{
  const int corners = NodalCornerCount(type);
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = hi[d] = points[3 * nodes[0] + d];
  }
  for (int k = 1; k < corners; ++k)
  {
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min(lo[d], points[3 * nodes[k] + d]);
      hi[d] = std::max(hi[d], points[3 * nodes[k] + d]);
    }
  }
  const double size = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) +
    (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  double largest = 0.0;
  for (const EdgeMid& e : EdgeMids(type))
  {
    const double* a = points + 3 * nodes[e.A];
    const double* b = points + 3 * nodes[e.B];
    const double* m = points + 3 * nodes[e.Mid];
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      const double o = m[d] - 0.5 * (a[d] + b[d]);
      d2 += o * o;
    }
    largest = std::max(largest, std::sqrt(d2));
  }
  const double l = std::max(level, 1);
  return size > 0.0 ? largest / (4.0 * l * l * size) : 0.0;
}

std::size_t CurvedSplitter::NameHash::operator()(const Name& n) const
{
  size_t h = 0;
  for (Index v : n)
  {
    h = h * 1000003u ^ std::hash<Index>()(v);
  }
  return h;
}

CurvedSplitter::CurvedSplitter(const double* points, Index firstNew, int level, const Index* keys)
  : Points(points)
  , FirstNew(firstNew)
  , Order(2 * level)
  , Keys(keys)
{}

void CurvedSplitter::Lattice(NodalType type, const Index* nodes)
{
  const int n = this->Order;
  this->Lat.clear();
  this->Simplex.clear();
  auto add = [&](int w0, int w1, int w2, int w3) {
    Local p{ { w0, w1, w2, w3 }, { 0, 0, 0 }, -1 };
    this->Place(type, nodes, p);
    this->Lat.push_back(p);
  };
  if (type == NodalType::Edge3)
  {
    for (int i = 0; i <= n; ++i)
    {
      add(n - i, i, 0, 0);
    }
    for (int i = 0; i < n; ++i)
    {
      this->Simplex.insert(this->Simplex.end(), { i, i + 1 });
    }
    return;
  }
  if (IsQuad(type))
  {
    // (i, j) at index j (n + 1) + i; W holds the tensor coordinates.
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i <= n; ++i)
      {
        add(i, j, 0, 0);
      }
    }
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const int p00 = j * (n + 1) + i;
        const int p10 = p00 + 1, p01 = p00 + n + 1, p11 = p01 + 1;
        this->Simplex.insert(this->Simplex.end(), { p00, p10, p11, p00, p11, p01 });
      }
    }
    return;
  }
  if (type == NodalType::Triangle6)
  {
    // (i, j), i + j <= n, at index Row(j) + i.
    std::vector<int> row(static_cast<size_t>(n + 2), 0);
    for (int j = 0; j <= n; ++j)
    {
      row[j + 1] = row[j] + (n - j + 1);
      for (int i = 0; i + j <= n; ++i)
      {
        add(n - i - j, i, j, 0);
      }
    }
    auto at = [&](int i, int j) { return row[j] + i; };
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i + j < n; ++i)
      {
        this->Simplex.insert(this->Simplex.end(), { at(i, j), at(i + 1, j), at(i, j + 1) });
        if (i + j + 1 < n)
        {
          this->Simplex.insert(
            this->Simplex.end(), { at(i + 1, j), at(i + 1, j + 1), at(i, j + 1) });
        }
      }
    }
    return;
  }
  // Tetra10: Kuhn's subdivision of the ordered simplex n >= u1 >= u2 >= u3 >= 0,
  // the image of the cell under weights w1 = u1 - u2, w2 = u2 - u3, w3 = u3.
  std::vector<int> index(static_cast<size_t>((n + 1) * (n + 1) * (n + 1)), -1);
  auto key = [&](int u1, int u2, int u3) { return (u1 * (n + 1) + u2) * (n + 1) + u3; };
  for (int u1 = 0; u1 <= n; ++u1)
  {
    for (int u2 = 0; u2 <= u1; ++u2)
    {
      for (int u3 = 0; u3 <= u2; ++u3)
      {
        index[key(u1, u2, u3)] = static_cast<int>(this->Lat.size());
        add(n - u1, u1 - u2, u2 - u3, u3);
      }
    }
  }
  static const int permutations[6][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 },
    { 2, 0, 1 }, { 2, 1, 0 } };
  for (int a = 0; a < n; ++a)
  {
    for (int b = 0; b <= a; ++b)
    {
      for (int c = 0; c <= b; ++c)
      {
        for (const auto& perm : permutations)
        {
          int u[3] = { a, b, c };
          int ids[4];
          bool inside = true;
          for (int s = 0; s < 4 && inside; ++s)
          {
            if (s > 0)
            {
              ++u[perm[s - 1]];
            }
            inside = u[0] <= n && u[0] >= u[1] && u[1] >= u[2];
            ids[s] = inside ? index[key(u[0], u[1], u[2])] : -1;
          }
          if (!inside)
          {
            continue;
          }
          // Positive in the reference tetrahedron (xi = (w1, w2, w3) / n).
          double m[3][3];
          for (int r = 0; r < 3; ++r)
          {
            for (int col = 0; col < 3; ++col)
            {
              m[r][col] = this->Lat[ids[r + 1]].W[col + 1] - this->Lat[ids[0]].W[col + 1];
            }
          }
          if (Determinant3(m) < 0.0)
          {
            std::swap(ids[2], ids[3]);
          }
          this->Simplex.insert(this->Simplex.end(), ids, ids + 4);
        }
      }
    }
  }
}

void CurvedSplitter::Place(NodalType type, const Index* nodes, Local& p) const
{
  const int n = this->Order;
  const int half = n / 2;
  if (IsQuad(type))
  {
    const int i = p.W[0], j = p.W[1];
    const bool iEnd = i == 0 || i == n, jEnd = j == 0 || j == n;
    if (iEnd && jEnd)
    {
      p.Id = nodes[QuadCorner(i, j, n)];
    }
    else if (jEnd) // on edge (0, 1) or (3, 2), from corner 0 or 3
    {
      this->PlaceOnEdge(type, nodes, QuadCorner(0, j, n), QuadCorner(n, j, n), n - i, p);
    }
    else if (iEnd) // on edge (0, 3) or (1, 2)
    {
      this->PlaceOnEdge(type, nodes, QuadCorner(i, 0, n), QuadCorner(i, n, n), n - j, p);
    }
    else if (type == NodalType::Quad9 && i == half && j == half)
    {
      p.Id = nodes[8];
    }
    if (p.Id >= 0 || iEnd || jEnd)
    {
      if (p.Id >= 0)
      {
        std::copy(this->Points + 3 * p.Id, this->Points + 3 * p.Id + 3, p.X);
      }
      return;
    }
    const double xi[3] = { double(i) / n, double(j) / n, 0.0 };
    double shape[27];
    NodalValues(type, xi, shape);
    for (int k = 0; k < NodalNodeCount(type); ++k)
    {
      for (int d = 0; d < 3; ++d)
      {
        p.X[d] += shape[k] * this->Points[3 * nodes[k] + d];
      }
    }
    return;
  }
  int c[4], w[4], m = 0;
  const int corners = NodalCornerCount(type);
  for (int k = 0; k < corners; ++k)
  {
    if (p.W[k] > 0)
    {
      c[m] = k;
      w[m++] = p.W[k];
    }
  }
  if (m == 1)
  {
    p.Id = nodes[c[0]];
  }
  else if (m == 2)
  {
    this->PlaceOnEdge(type, nodes, c[0], c[1], w[0], p);
    return;
  }
  else if (m == 3 && type == NodalType::Tetra10)
  {
    this->PlaceOnFace(nodes, { c[0], c[1], c[2] }, { w[0], w[1], w[2] }, p);
    return;
  }
  if (p.Id >= 0)
  {
    std::copy(this->Points + 3 * p.Id, this->Points + 3 * p.Id + 3, p.X);
    return;
  }
  // Inside the cell: its own map.
  const double xi[3] = { double(p.W[1]) / n, double(p.W[2]) / n, double(p.W[3]) / n };
  double shape[27];
  NodalValues(type, xi, shape);
  for (int k = 0; k < NodalNodeCount(type); ++k)
  {
    for (int d = 0; d < 3; ++d)
    {
      p.X[d] += shape[k] * this->Points[3 * nodes[k] + d];
    }
  }
}

void CurvedSplitter::PlaceOnEdge(
  NodalType type, const Index* nodes, int a, int b, int wa, Local& p) const
{
  const int n = this->Order;
  const Index mid = nodes[MidOf(type, a, b)];
  if (2 * wa == n)
  {
    p.Id = mid;
    std::copy(this->Points + 3 * mid, this->Points + 3 * mid + 3, p.X);
    return;
  }
  // From the end of lower key: both cells on the edge compute these bits.
  Index from = nodes[a], to = nodes[b];
  int w = wa;
  if (this->KeyOf(to) < this->KeyOf(from))
  {
    std::swap(from, to);
    w = n - wa;
  }
  const double t = double(n - w) / n; // 0 at `from`
  const double nf = (1.0 - t) * (1.0 - 2.0 * t), nt = t * (2.0 * t - 1.0), nm = 4.0 * t * (1.0 - t);
  for (int d = 0; d < 3; ++d)
  {
    p.X[d] = nf * this->Points[3 * from + d] + nt * this->Points[3 * to + d] +
      nm * this->Points[3 * mid + d];
  }
}

void CurvedSplitter::PlaceOnFace(
  const Index* nodes, const int (&c)[3], const int (&w)[3], Local& p) const
{
  // The face's corners in the order of their keys, and their mid nodes.
  int order[3] = { 0, 1, 2 };
  std::sort(order, order + 3,
    [&](int x, int y) { return this->KeyOf(nodes[c[x]]) < this->KeyOf(nodes[c[y]]); });
  double lambda[3];
  Index corner[3];
  for (int k = 0; k < 3; ++k)
  {
    lambda[k] = double(w[order[k]]) / this->Order;
    corner[k] = nodes[c[order[k]]];
  }
  const Index m01 = nodes[MidOf(NodalType::Tetra10, c[order[0]], c[order[1]])];
  const Index m12 = nodes[MidOf(NodalType::Tetra10, c[order[1]], c[order[2]])];
  const Index m02 = nodes[MidOf(NodalType::Tetra10, c[order[0]], c[order[2]])];
  for (int d = 0; d < 3; ++d)
  {
    double x = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      x += lambda[k] * (2.0 * lambda[k] - 1.0) * this->Points[3 * corner[k] + d];
    }
    x += 4.0 * lambda[0] * lambda[1] * this->Points[3 * m01 + d];
    x += 4.0 * lambda[1] * lambda[2] * this->Points[3 * m12 + d];
    x += 4.0 * lambda[0] * lambda[2] * this->Points[3 * m02 + d];
    p.X[d] = x;
  }
}

bool CurvedSplitter::OneSigned(NodalType type, const Index* nodes) const
{
  const int corners = NodalCornerCount(type);
  const double* x0 = this->Points + 3 * nodes[0];
  if (type == NodalType::Edge3)
  {
    const double* x1 = this->Points + 3 * nodes[1];
    for (size_t s = 0; s < this->Simplex.size(); s += 2)
    {
      const double* a = this->Lat[this->Simplex[s]].X;
      const double* b = this->Lat[this->Simplex[s + 1]].X;
      double along = 0.0;
      for (int d = 0; d < 3; ++d)
      {
        along += (b[d] - a[d]) * (x1[d] - x0[d]);
      }
      if (!(along > 0.0))
      {
        return false;
      }
    }
    return true;
  }
  if (type == NodalType::Tetra10)
  {
    // One sign throughout (VTK's positive cells give positive simplices).
    int sign = 0;
    for (size_t s = 0; s < this->Simplex.size(); s += 4)
    {
      const int* v = &this->Simplex[s];
      const double six =
        Orient3D(this->Lat[v[0]].X, this->Lat[v[1]].X, this->Lat[v[2]].X, this->Lat[v[3]].X);
      const int here = six > 0.0 ? 1 : (six < 0.0 ? -1 : 0);
      if (here == 0 || (sign != 0 && here != sign))
      {
        return false;
      }
      sign = here;
    }
    return true;
  }
  // 2D: against the (Newell) normal of the corners' outline.
  double normal[3] = { 0, 0, 0 };
  for (int k = 0; k < corners; ++k)
  {
    const double* a = this->Points + 3 * nodes[k];
    const double* b = this->Points + 3 * nodes[(k + 1) % corners];
    normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
    normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
    normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  for (size_t s = 0; s < this->Simplex.size(); s += 3)
  {
    const double* a = this->Lat[this->Simplex[s]].X;
    const double* b = this->Lat[this->Simplex[s + 1]].X;
    const double* c = this->Lat[this->Simplex[s + 2]].X;
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    const double along = (u[1] * v[2] - u[2] * v[1]) * normal[0] +
      (u[2] * v[0] - u[0] * v[2]) * normal[1] + (u[0] * v[1] - u[1] * v[0]) * normal[2];
    if (!(along > 0.0))
    {
      return false;
    }
  }
  return true;
}

Index CurvedSplitter::IdOf(NodalType type, const Index* nodes, Local& p)
{
  if (p.Id >= 0)
  {
    return p.Id;
  }
  // Shared when it lies on an edge or (for a tetrahedron) a face: named by
  // its corners' ids and weights there.
  Name name;
  name.fill(-1);
  int m = 0;
  if (IsQuad(type))
  {
    const int n = this->Order;
    const int i = p.W[0], j = p.W[1];
    if (j == 0 || j == n)
    {
      name = { nodes[QuadCorner(0, j, n)], n - i, nodes[QuadCorner(n, j, n)], i, -1, -1 };
      m = 2;
    }
    else if (i == 0 || i == n)
    {
      name = { nodes[QuadCorner(i, 0, n)], n - j, nodes[QuadCorner(i, n, n)], j, -1, -1 };
      m = 2;
    }
  }
  else
  {
    const int corners = NodalCornerCount(type);
    for (int k = 0; k < corners; ++k)
    {
      if (p.W[k] > 0)
      {
        if (m < 3) // (a point with four: inside a tetrahedron, named below as its own)
        {
          name[2 * m] = nodes[k];
          name[2 * m + 1] = p.W[k];
        }
        ++m;
      }
    }
    m = m < corners ? m : 0; // inside the cell: its own
  }
  if (m > 0)
  {
    // Pairs by ascending id.
    std::array<std::pair<Index, Index>, 3> pairs;
    for (int k = 0; k < 3; ++k)
    {
      pairs[k] =
        k < m ? std::make_pair(name[2 * k], name[2 * k + 1]) : std::make_pair(Index(-1), Index(-1));
    }
    std::sort(pairs.begin(), pairs.begin() + m);
    for (int k = 0; k < 3; ++k)
    {
      name[2 * k] = pairs[k].first;
      name[2 * k + 1] = pairs[k].second;
    }
    const auto found = this->Shared.find(name);
    if (found != this->Shared.end())
    {
      return found->second;
    }
  }
  const Index id = this->FirstNew + this->AddedCount();
  this->Added.insert(this->Added.end(), p.X, p.X + 3);
  if (m > 0)
  {
    this->Shared.emplace(name, id);
  }
  return id;
}

bool CurvedSplitter::Split(NodalType type, const Index* nodes, std::vector<Index>& simplices)
{
  if (this->Order < 4 || !IsRefinedWhenCurved(type))
  {
    return false;
  }
  this->Lattice(type, nodes);
  if (!this->OneSigned(type, nodes))
  {
    return false;
  }
  std::vector<Index> ids(this->Lat.size());
  for (size_t k = 0; k < this->Lat.size(); ++k)
  {
    ids[k] = this->IdOf(type, nodes, this->Lat[k]);
  }
  for (int v : this->Simplex)
  {
    simplices.push_back(ids[static_cast<size_t>(v)]);
  }
  return true;
}
} // namespace mp
