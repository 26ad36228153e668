// SPDX-License-Identifier: BSD-3-Clause
#include "Search/SupportingFaces.h"

#include "Geometry/Predicates.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <utility>

namespace mp
{
namespace
{
/// A k-d tree of boxes over points, for "is every point on one side of
/// this plane?".
class PointTree
{
public:
  PointTree(const double* x, std::vector<Index> ids)
    : X(x)
    , Ids(std::move(ids))
  {
    this->Nodes.reserve(2 * (this->Ids.size() / LeafSize + 1));
    this->Nodes.emplace_back();
    this->Build(0, 0, static_cast<Index>(this->Ids.size()));
  }

  /**
   * 1 when every point lies in the closed half-space of plane (a, b, c)
   * where Orient3D(a, b, c, .) has the sign `side` (+1 or -1) or is zero,
   * 0 when one does not, -1 when `budget` did not tell: a node visit
   * costs 1, an exact evaluation (a point on or near the plane) 16. Also
   * -1 where the bounds' arithmetic could overflow or underflow.
   */
  int AllOnSide(const double* a, const double* b, const double* c, double side, Index budget) const
  {
    double e1[3];
    double e2[3];
    double scale1 = 0.0;
    double scale2 = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      e1[d] = b[d] - a[d];
      e2[d] = c[d] - a[d];
      scale1 = std::max(scale1, std::fabs(e1[d]));
      scale2 = std::max(scale2, std::fabs(e2[d]));
    }
    // Orient3D(a, b, c, v) = n . (v - a) with n = e1 x e2; `outward` points
    // to the side that must hold no point.
    const double outward[3] = { -side * (e1[1] * e2[2] - e1[2] * e2[1]),
      -side * (e1[2] * e2[0] - e1[0] * e2[2]), -side * (e1[0] * e2[1] - e1[1] * e2[0]) };
    // The rounded normal is within 12 u |e1|max |e2|max of the exact one
    // per component, and the rounded bound of a box below within 8 u |n|
    // per unit of `reach`: with this slack a box below -slack * reach holds
    // no point on the plane or beyond it.
    const double slack = 256.0 * RoundingUnit * scale1 * scale2;
    // The error model holds for normal numbers only: every term below is
    // at most the normal's scale times the reach of the tree's box.
    const double largest = 8.0 * scale1 * scale2 * this->Reach(a);
    if (!(largest < 1e300) || !(largest > 1e-280))
    {
      return -1;
    }
    std::array<Index, 128> stack;
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
      const Node& node = this->Nodes[static_cast<size_t>(stack[--top])];
      if (--budget < 0)
      {
        return -1;
      }
      double bound = 0.0;
      double reach = 0.0;
      for (int d = 0; d < 3; ++d)
      {
        const double lo = node.Lo[d] - a[d];
        const double hi = node.Hi[d] - a[d];
        bound += std::max(outward[d] * lo, outward[d] * hi);
        reach += std::max(std::fabs(lo), std::fabs(hi));
      }
      if (bound < -slack * reach)
      {
        continue; // every point of the box strictly inside
      }
      if (node.Child < 0)
      {
        for (Index i = node.Begin; i < node.End; ++i)
        {
          // The same bound for the point alone, then the exact sign.
          const double* x = this->X + 3 * this->Ids[static_cast<size_t>(i)];
          double value = 0.0;
          double distance = 0.0;
          for (int d = 0; d < 3; ++d)
          {
            value += outward[d] * (x[d] - a[d]);
            distance += std::fabs(x[d] - a[d]);
          }
          if (!(value < -slack * distance))
          {
            budget -= 16;
            if (!OnSide(a, b, c, x, side))
            {
              return 0;
            }
          }
        }
        continue;
      }
      if (top + 2 > static_cast<int>(stack.size()))
      {
        return -1; // deeper than any tree built here
      }
      stack[top++] = node.Child;
      stack[top++] = node.Child + 1;
    }
    return 1;
  }

private:
  /// The largest |v - a|_1 over the root's box (0 for an empty tree).
  double Reach(const double* a) const
  {
    if (this->Ids.empty())
    {
      return 0.0;
    }
    const Node& root = this->Nodes[0];
    double reach = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      reach += std::max(std::fabs(root.Lo[d] - a[d]), std::fabs(root.Hi[d] - a[d]));
    }
    return reach;
  }

  static constexpr Index LeafSize = 8;
  struct Node
  {
    double Lo[3];
    double Hi[3];
    Index Begin;
    Index End;
    Index Child; ///< the first of two children, or -1 for a leaf
  };

  void Build(Index at, Index begin, Index end)
  {
    Node node;
    node.Begin = begin;
    node.End = end;
    node.Child = -1;
    for (int d = 0; d < 3; ++d)
    {
      node.Lo[d] = HUGE_VAL;
      node.Hi[d] = -HUGE_VAL;
    }
    for (Index i = begin; i < end; ++i)
    {
      const double* x = this->X + 3 * this->Ids[static_cast<size_t>(i)];
      for (int d = 0; d < 3; ++d)
      {
        node.Lo[d] = std::min(node.Lo[d], x[d]);
        node.Hi[d] = std::max(node.Hi[d], x[d]);
      }
    }
    if (end - begin > LeafSize)
    {
      int axis = 0;
      for (int d = 1; d < 3; ++d)
      {
        if (node.Hi[d] - node.Lo[d] > node.Hi[axis] - node.Lo[axis])
        {
          axis = d;
        }
      }
      const Index middle = begin + (end - begin) / 2;
      const double* x = this->X;
      std::nth_element(this->Ids.begin() + begin, this->Ids.begin() + middle,
        this->Ids.begin() + end,
        [x, axis](Index p, Index q) { return x[3 * p + axis] < x[3 * q + axis]; });
      node.Child = static_cast<Index>(this->Nodes.size());
      this->Nodes.emplace_back();
      this->Nodes.emplace_back();
      this->Nodes[static_cast<size_t>(at)] = node;
      this->Build(node.Child, begin, middle);
      this->Build(node.Child + 1, middle, end);
      return;
    }
    this->Nodes[static_cast<size_t>(at)] = node;
  }

  /// Whether x is on the plane or on the `side` of it, exactly (the
  /// plane's own corners without an exact evaluation of 0).
  static bool OnSide(
    const double* a, const double* b, const double* c, const double* x, double side)
  {
    auto same = [x](const double* p) { return x[0] == p[0] && x[1] == p[1] && x[2] == p[2]; };
    return same(a) || same(b) || same(c) || Orient3D(a, b, c, x) * side >= 0.0;
  }

  const double* X;
  std::vector<Index> Ids;
  std::vector<Node> Nodes;
};

/// A face without neighbour: face K of cell Cell.
struct BoundaryFace
{
  Index Cell;
  int K;
};

/// Corner j (0..2) of face f.
inline Index FaceCorner(const MeshView& mesh, const BoundaryFace& f, int j)
{
  return mesh.Cell(f.Cell)[(f.K + 1 + j) % 4];
}

/// The faces without neighbour of `cells`.
std::vector<BoundaryFace> FacesWithoutNeighbour(
  const MeshView& mesh, const std::vector<Index>& cells)
{
  std::vector<BoundaryFace> faces;
  for (const Index c : cells)
  {
    for (int k = 0; k < 4; ++k)
    {
      if (mesh.Neighbor(c, k) < 0)
      {
        faces.push_back({ c, k });
      }
    }
  }
  return faces;
}

/// The questions asked of a boundary face: its points, the side of its
/// plane a point is on, and whether the plane supports the mesh (every
/// boundary corner in `tree` on its cell's side).
class FaceTests
{
public:
  FaceTests(const MeshView& mesh, const PointTree& tree)
    : Mesh(mesh)
    , Tree(tree)
  {}
  Index Corner(const BoundaryFace& f, int j) const { return FaceCorner(this->Mesh, f, j); }
  /// The corner of f's cell off f.
  Index Opposite(const BoundaryFace& f) const { return this->Mesh.Cell(f.Cell)[f.K]; }
  /// Which side of face f's plane point p is on (0: on it).
  int SideOf(const BoundaryFace& f, Index p) const
  {
    const MeshView& mesh = this->Mesh;
    const double o = Orient3D(mesh.Point(this->Corner(f, 0)), mesh.Point(this->Corner(f, 1)),
      mesh.Point(this->Corner(f, 2)), mesh.Point(p));
    return o > 0.0 ? 1 : (o < 0.0 ? -1 : 0);
  }
  /// 1 supports, 0 does not, -1 undecided within `budget` (AllOnSide).
  int Supports(const BoundaryFace& f, Index budget) const
  {
    const MeshView& mesh = this->Mesh;
    const int inner = this->SideOf(f, this->Opposite(f));
    return inner == 0
      ? 0
      : this->Tree.AllOnSide(mesh.Point(this->Corner(f, 0)), mesh.Point(this->Corner(f, 1)),
          mesh.Point(this->Corner(f, 2)), inner, budget);
  }

private:
  const MeshView& Mesh;
  const PointTree& Tree;
};

/**
 * The faces' corners, all finite (else false: no face supports the mesh):
 * the cells of positive volume lie in the hull of those (the source's
 * extreme points are on its boundary, which those faces cover).
 */
bool BoundaryCorners(
  const MeshView& mesh, const std::vector<BoundaryFace>& faces, std::vector<Index>& ids)
{
  std::vector<char> used(static_cast<size_t>(mesh.AllPoints()), 0);
  for (const BoundaryFace& f : faces)
  {
    for (int j = 0; j < 3; ++j)
    {
      const Index p = FaceCorner(mesh, f, j);
      if (p < 0 || p >= mesh.AllPoints())
      {
        return false;
      }
      if (!used[static_cast<size_t>(p)])
      {
        used[static_cast<size_t>(p)] = 1;
        const double* x = mesh.Point(p);
        if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
        {
          return false;
        }
        ids.push_back(p);
      }
    }
  }
  return true;
}

Index Root(std::vector<Index>& parent, Index i)
{
  while (parent[static_cast<size_t>(i)] != i)
  {
    Index& p = parent[static_cast<size_t>(i)];
    p = parent[static_cast<size_t>(p)];
    i = p;
  }
  return i;
}

/**
 * Planes: faces that share an edge, lie exactly in one plane and have
 * their cells on one side of it are one (union-find): per face of
 * `crowded`, a link toward its plane's root (Root).
 */
std::vector<Index> CoplanarFaces(const FaceTests& tests, const std::vector<BoundaryFace>& crowded)
{
  struct Edge
  {
    Index Low;
    Index High;
    Index Face;
    bool operator<(const Edge& o) const
    {
      return this->Low != o.Low
        ? this->Low < o.Low
        : (this->High != o.High ? this->High < o.High : this->Face < o.Face);
    }
  };
  std::vector<Edge> edges;
  edges.reserve(3 * crowded.size());
  for (size_t f = 0; f < crowded.size(); ++f)
  {
    for (int j = 0; j < 3; ++j)
    {
      const Index p = tests.Corner(crowded[f], j);
      const Index q = tests.Corner(crowded[f], (j + 1) % 3);
      edges.push_back({ std::min(p, q), std::max(p, q), static_cast<Index>(f) });
    }
  }
  std::sort(edges.begin(), edges.end());
  auto sameEdge = [&](size_t e, size_t g) {
    return edges[e].Low == edges[g].Low && edges[e].High == edges[g].High;
  };
  std::vector<Index> plane(crowded.size());
  std::iota(plane.begin(), plane.end(), Index(0));
  for (size_t e = 0; e + 1 < edges.size(); ++e)
  {
    // Only edges of exactly two of these faces.
    if (!sameEdge(e, e + 1) || (e + 2 < edges.size() && sameEdge(e, e + 2)) ||
      (e > 0 && sameEdge(e - 1, e)))
    {
      continue;
    }
    const BoundaryFace& fa = crowded[static_cast<size_t>(edges[e].Face)];
    const BoundaryFace& fb = crowded[static_cast<size_t>(edges[e + 1].Face)];
    Index apex = -1; // fb's corner off the edge
    for (int j = 0; j < 3; ++j)
    {
      const Index p = tests.Corner(fb, j);
      apex = (p != edges[e].Low && p != edges[e].High) ? p : apex;
    }
    const int inner = tests.SideOf(fa, tests.Opposite(fa));
    if (apex >= 0 && inner != 0 && tests.SideOf(fa, apex) == 0 &&
      tests.SideOf(fa, tests.Opposite(fb)) == inner)
    {
      plane[static_cast<size_t>(Root(plane, edges[e].Face))] = Root(plane, edges[e + 1].Face);
    }
  }
  return plane;
}
} // namespace

std::vector<unsigned char> SupportingFaces(const MeshView& mesh, const std::vector<Index>& cells)
{
  std::vector<unsigned char> flags;
  if (mesh.CellDimension != 3 || mesh.SpaceDimension != 3 || !mesh.Neighbors)
  {
    return flags;
  }
  flags.assign(static_cast<size_t>(mesh.NumberOfCells), 0);
  const std::vector<BoundaryFace> faces = FacesWithoutNeighbour(mesh, cells);
  std::vector<Index> ids;
  if (!BoundaryCorners(mesh, faces, ids))
  {
    return flags;
  }
  const PointTree tree(mesh.Points, std::move(ids));
  const FaceTests tests(mesh, tree);
  auto mark = [&](const BoundaryFace& f) {
    flags[static_cast<size_t>(f.Cell)] |= static_cast<unsigned char>(1u << f.K);
  };

  // Each face on its own first (on a curved boundary a few dozen visits
  // tell); those with many points on or near their plane then together
  // with the faces of the same plane.
  std::vector<BoundaryFace> crowded;
  for (const BoundaryFace& f : faces)
  {
    const int supports = tests.Supports(f, 256);
    if (supports == 1)
    {
      mark(f);
    }
    else if (supports < 0)
    {
      crowded.push_back(f);
    }
  }
  if (crowded.empty())
  {
    return flags;
  }
  std::vector<Index> plane = CoplanarFaces(tests, crowded);
  std::vector<Index> facesOnPlane(crowded.size(), 0);
  for (size_t f = 0; f < crowded.size(); ++f)
  {
    ++facesOnPlane[static_cast<size_t>(Root(plane, static_cast<Index>(f)))];
  }
  std::vector<signed char> supports(crowded.size(), -1);
  for (size_t f = 0; f < crowded.size(); ++f)
  {
    const size_t root = static_cast<size_t>(Root(plane, static_cast<Index>(f)));
    if (supports[root] < 0)
    {
      supports[root] = tests.Supports(crowded[root], 512 + 32 * facesOnPlane[root]) == 1;
    }
    if (supports[root] == 1)
    {
      mark(crowded[f]);
    }
  }
  return flags;
}
} // namespace mp
