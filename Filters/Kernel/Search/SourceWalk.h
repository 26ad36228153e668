// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SourceWalk.h
 * @brief How the advancing front (PairSearch.h) finds a seed without the
 *        locator: a cache of prepared source cells, the sampled starts and
 *        the visibility walk through the source mesh toward a point.
 */
#ifndef MeshProjection_Kernel_SourceWalk_h
#define MeshProjection_Kernel_SourceWalk_h

#include "Mesh/MeshView.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace mp
{
/**
 * A small direct-mapped cache of prepared source cells. The front visits the
 * source cells around a region many times in a row (each about as often as
 * it meets target cells), so a few thousand slots avoid most re-preparations
 * at a fixed, small memory cost.
 */
template <class Intersector>
class PreparedCells
{
public:
  static constexpr Index Slots = 4096; // a power of two
  /// `degenerate`, when given, collects the ids of cells of zero measure
  /// met (with repeats).
  explicit PreparedCells(const MeshView& mesh, std::vector<Index>* degenerate = nullptr)
    : Mesh(mesh)
    , Degenerate(degenerate)
    , Ids(Slots, -1)
    , Valid(Slots, 0)
    , Cells(Slots)
  {}
  /// The prepared cell, or null for a cell of zero measure.
  const typename Intersector::Cell* Get(Index id)
  {
    const Index slot = id & (Slots - 1);
    if (this->Ids[slot] != id)
    {
      this->Ids[slot] = id;
      this->Valid[slot] = Intersector::Prepare(this->Mesh, id, this->Cells[slot]);
      if (!this->Valid[slot] && this->Degenerate)
      {
        this->Degenerate->push_back(id);
      }
    }
    return this->Valid[slot] ? &this->Cells[slot] : nullptr;
  }

private:
  const MeshView& Mesh;
  std::vector<Index>* Degenerate;
  std::vector<Index> Ids;
  std::vector<char> Valid;
  std::vector<typename Intersector::Cell> Cells;
};

/**
 * Other starts for walks: about 2 sqrt(n) source cells at a regular stride of
 * ids, with their centres, gathered on the first question. A walk from the
 * last source cell met stops where a hole or a bay of the source lies on its
 * way; one from the sampled cell nearest the point is short, so it seldom
 * meets one, and saves the query among all source cells (and the index over
 * all of them that it builds). Ids spread the samples over the mesh for any
 * numbering that is not adversarial; the start is a heuristic, the search's
 * result does not depend on it.
 */
class WalkStarts
{
public:
  explicit WalkStarts(const MeshView& mesh)
    : Mesh(mesh)
  {}
  /// How many cells are sampled: about 2 sqrt(n).
  static Index Samples(Index n)
  {
    return std::min<Index>(n, 2 * static_cast<Index>(std::sqrt(static_cast<double>(n))) + 1);
  }
  /// The sampled cell whose centre is nearest q (the mesh's first
  /// SpaceDimension coordinates), or -1 for a mesh without cells. Costs
  /// Samples() steps.
  Index Nearest(const double* q)
  {
    const MeshView& m = this->Mesh;
    const int dims = m.SpaceDimension;
    if (this->Ids.empty() && m.NumberOfCells > 0)
    {
      const Index n = m.NumberOfCells;
      const Index samples = Samples(n);
      const int corners = m.CornersPerCell();
      for (Index i = 0; i < samples; ++i)
      {
        const Index c = static_cast<Index>((2 * i + 1) * n / (2 * samples));
        const CellCorners ids = m.Cell(c);
        double centre[3] = { 0.0, 0.0, 0.0 };
        for (int k = 0; k < corners; ++k)
        {
          for (int d = 0; d < dims; ++d)
          {
            centre[d] += m.Point(ids[k])[d] / corners;
          }
        }
        this->Ids.push_back(c);
        this->Centres.insert(this->Centres.end(), centre, centre + dims);
      }
    }
    Index best = -1;
    double nearest = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < this->Ids.size(); ++i)
    {
      double d2 = 0.0;
      for (int d = 0; d < dims; ++d)
      {
        const double e = this->Centres[i * dims + d] - q[d];
        d2 += e * e;
      }
      if (d2 < nearest)
      {
        nearest = d2;
        best = this->Ids[i];
      }
    }
    return best;
  }

private:
  const MeshView& Mesh;
  std::vector<Index> Ids;
  std::vector<double> Centres; ///< SpaceDimension coordinates per sample
};

/**
 * Walks from source cell `start` toward point q (PairSearch.h's file comment): the
 * source cell whose closure holds q, or -1 when the walk reaches the
 * boundary, a cell of zero measure or `maxSteps`. The face tried first turns
 * from step to step, so that a walk cannot circle for long in a mesh that is
 * not Delaunay.
 */
template <class Intersector>
Index WalkToward(const MeshView& source, PreparedCells<Intersector>& cells, Index start,
  const double* q, Index maxSteps, Index& steps)
{
  Index current = start;
  for (Index step = 0; step < maxSteps && current >= 0; ++step)
  {
    ++steps;
    const typename Intersector::Cell* c = cells.Get(current);
    if (!c)
    {
      return -1;
    }
    const int k = Intersector::Locate(*c, q, static_cast<int>(step % Intersector::Faces));
    if (k < 0)
    {
      return current;
    }
    current = source.Neighbor(current, c->Face[k]);
  }
  return -1;
}
} // namespace mp

#endif
