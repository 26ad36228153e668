// SPDX-License-Identifier: BSD-3-Clause
// The root extension of the fringe on second-order targets (FringeRoots.h):
// which parents can be roots, and the weights of the best one.
#include "Transfer/FringeRoots.h"

#include "Geometry/NodalShapes.h"
#include "Mesh/NodalCells.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mp
{
namespace
{
/// A candidate root: its amplification, its nodes' centroid, its parent.
struct Candidate
{
  double Amplification;
  double Centroid[3];
  Index Parent;
};

/// Orders candidates by amplification, then by centroid (never by the numbering).
bool Before(const Candidate& a, const Candidate& b)
{
  if (a.Amplification != b.Amplification)
  {
    return a.Amplification < b.Amplification;
  }
  return std::lexicographical_compare(a.Centroid, a.Centroid + 3, b.Centroid, b.Centroid + 3);
}

/// Parent p's node coordinates (3 per node, in the type's order); their count.
int NodesOf(const MeshView& mesh, Index p, double* X)
{
  const long long begin = mesh.Nodal->Offsets[p];
  const int count = static_cast<int>(mesh.Nodal->Offsets[p + 1] - begin);
  for (int n = 0; n < count; ++n)
  {
    const double* x = mesh.Point(static_cast<Index>(mesh.Nodal->Nodes[begin + n]));
    std::copy(x, x + 3, X + 3 * n);
  }
  return count;
}

/// Parent p's weights at point i (the shape functions at i's reference
/// coordinates) and their amplification; false when the inverse fails.
bool WeightsAt(const MeshView& mesh, Index p, Index i, double* N, Candidate& candidate)
{
  const NodalType type = mesh.Nodal->Type[p];
  double X[3 * MaxNodalNodes];
  const int count = NodesOf(mesh, p, X);
  double xi[3] = { 0.0, 0.0, 0.0 };
  if (!NodalReference(type, X, mesh.SpaceDimension, mesh.Point(i), xi))
  {
    return false;
  }
  NodalValues(type, xi, N);
  candidate.Amplification = 0.0;
  std::fill(candidate.Centroid, candidate.Centroid + 3, 0.0);
  for (int n = 0; n < count; ++n)
  {
    candidate.Amplification += std::abs(N[n]);
    for (int a = 0; a < 3; ++a)
    {
      candidate.Centroid[a] += X[3 * n + a] / count;
    }
  }
  candidate.Parent = p;
  return std::isfinite(candidate.Amplification);
}

/// Whether every node of parent p is usable.
bool AllUsable(const MeshView& mesh, Index p, const std::vector<char>& usable)
{
  for (long long q = mesh.Nodal->Offsets[p]; q < mesh.Nodal->Offsets[p + 1]; ++q)
  {
    if (!usable[static_cast<size_t>(mesh.Nodal->Nodes[q])])
    {
      return false;
    }
  }
  return true;
}
} // namespace

bool IsAffineRoot(const MeshView& mesh, Index p)
{
  const NodalType type = mesh.Nodal ? mesh.Nodal->Type[p] : NodalType::None;
  const int d = NodalCellDimension(type);
  if (type == NodalType::None || type == NodalType::Pyramid13 || d != mesh.SpaceDimension ||
    d != mesh.CellDimension)
  {
    return false;
  }
  double X[3 * MaxNodalNodes];
  const int count = NodesOf(mesh, p, X);
  if (type == NodalType::Quad9 || type == NodalType::Hexa27 || type == NodalType::Wedge18)
  {
    // (Their full tensor spaces reproduce every quadratic through the
    // corners' multilinear map too.)
    return NodalIsStraight(type, X, mesh.SpaceDimension, 1e-9);
  }
  double xi[3 * MaxNodalNodes];
  NodalReferenceNodes(type, xi);
  // The affine map through the corner at the reference origin and those at
  // the reference unit vectors; every node must lie on it.
  int axis[3] = { -1, -1, -1 };
  for (int n = 0; n < NodalCornerCount(type); ++n)
  {
    for (int a = 0; a < d; ++a)
    {
      bool unit = true;
      for (int b = 0; b < d; ++b)
      {
        unit = unit && xi[3 * n + b] == (a == b ? 1.0 : 0.0);
      }
      axis[a] = unit ? n : axis[a];
    }
  }
  double lo[3] = { X[0], X[1], X[2] };
  double hi[3] = { X[0], X[1], X[2] };
  for (int n = 0; n < count; ++n)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], X[3 * n + a]);
      hi[a] = std::max(hi[a], X[3 * n + a]);
    }
  }
  const double size = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) +
    (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  if (xi[0] != 0.0 || xi[1] != 0.0 || xi[2] != 0.0 || !(size > 0.0))
  {
    return false; // (every type's first node is its reference origin)
  }
  for (int n = 0; n < count; ++n)
  {
    double off2 = 0.0;
    for (int c = 0; c < d; ++c)
    {
      double x = X[c];
      for (int a = 0; a < d; ++a)
      {
        x += axis[a] < 0 ? 0.0 : xi[3 * n + a] * (X[3 * axis[a] + c] - X[c]);
      }
      off2 += (X[3 * n + c] - x) * (X[3 * n + c] - x);
    }
    if (std::sqrt(off2) > 1e-9 * size)
    {
      return false;
    }
  }
  return axis[0] >= 0 && axis[d - 1] >= 0;
}

bool RootExtension(const MeshView& mesh, Index i, const std::vector<Index>& cells,
  const std::vector<char>& root, const std::vector<char>& usable, std::vector<Index>& points,
  std::vector<double>& weights)
{
  points.clear();
  weights.clear();
  std::vector<Index> parents;
  for (Index c : cells)
  {
    const Index p = mesh.ParentOf(c);
    if (root[static_cast<size_t>(p)])
    {
      parents.push_back(p);
    }
  }
  std::sort(parents.begin(), parents.end());
  parents.erase(std::unique(parents.begin(), parents.end()), parents.end());
  double N[MaxNodalNodes];
  Candidate best{ FringeRootAmplification, { 0.0, 0.0, 0.0 }, -1 };
  bool found = false;
  for (Index p : parents)
  {
    Candidate candidate;
    if (AllUsable(mesh, p, usable) && WeightsAt(mesh, p, i, N, candidate) &&
      (candidate.Amplification <= FringeRootAmplification) && (!found || Before(candidate, best)))
    {
      best = candidate;
      found = true;
    }
  }
  if (!found)
  {
    return false;
  }
  WeightsAt(mesh, best.Parent, i, N, best);
  // Nearest first, ties by the coordinates: an order the numbering does not change.
  const double* xi = mesh.Point(i);
  std::vector<std::pair<double, int>> order;
  const long long begin = mesh.Nodal->Offsets[best.Parent];
  const int count = static_cast<int>(mesh.Nodal->Offsets[best.Parent + 1] - begin);
  for (int n = 0; n < count; ++n)
  {
    const double* x = mesh.Point(static_cast<Index>(mesh.Nodal->Nodes[begin + n]));
    double r2 = 0.0;
    for (int a = 0; a < mesh.SpaceDimension; ++a)
    {
      r2 += (x[a] - xi[a]) * (x[a] - xi[a]);
    }
    order.emplace_back(r2, n);
  }
  std::sort(order.begin(), order.end(), [&](const auto& a, const auto& b) {
    if (a.first != b.first)
    {
      return a.first < b.first;
    }
    const double* p = mesh.Point(static_cast<Index>(mesh.Nodal->Nodes[begin + a.second]));
    const double* q = mesh.Point(static_cast<Index>(mesh.Nodal->Nodes[begin + b.second]));
    return std::lexicographical_compare(p, p + 3, q, q + 3);
  });
  for (const auto& entry : order)
  {
    points.push_back(static_cast<Index>(mesh.Nodal->Nodes[begin + entry.second]));
    weights.push_back(N[entry.second]);
  }
  return true;
}
} // namespace mp
