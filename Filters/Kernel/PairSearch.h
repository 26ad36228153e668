// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PairSearch.h
 * @brief Finding all intersecting (target, source) cell pairs: the advancing
 *        front of Gander & Japhet and the brute-force oracle.
 *
 * The front (the paper's Fig. 2): every target cell is treated once. For a
 * target cell with a starting source candidate, an inner front walks over the
 * source cells' neighbours and keeps every source cell that meets it (only
 * across the source faces the target reaches, `Piece::SourceFaces`: any
 * other source cell meeting the convex target is reached through cells that
 * meet it); while doing so it records, for each face of the target cell, a
 * source cell meeting that face (`Intersector::FaceSeed`), a valid starting
 * candidate for the target neighbour across that face. Those neighbours join
 * the outer front. Work is linear in the number of intersecting pairs.
 *
 * The outer front is treated smallest target id first (a binary heap) rather
 * than first in, first out: on meshes stored with some locality the front
 * then sweeps both meshes roughly in storage order, so the source cells it
 * revisits are still in cache (the FIFO order makes diagonal waves that
 * touch the whole mesh at once). Any order finds the same pairs.
 *
 * Beyond the paper, nothing assumes that cell 0 meets cell 0, that the meshes
 * are connected or cover the same domain, or that a cell's intersection with
 * the other mesh is connected:
 *  - target cells the front has not reached are seeded from the
 *    CandidateLocator, one query each (so disjoint parts, holes and partial
 *    overlaps are all found);
 *  - when the inner front of a target cell touches the source mesh's boundary
 *    (where its intersection may be disconnected), or its seed fails, the
 *    locator's candidates for that cell are added to the inner front.
 *
 * Meeting is decided with exact predicates (in 2D on closed cells, so cells
 * that only touch in a vertex or along an edge keep the fronts going; in 3D
 * by positive volume, with seeds through shared faces), and both searches
 * find exactly the same pairs.
 *
 * `Intersector` is the cell-pair geometry (TriangleIntersector in 2D); the
 * search itself does not depend on the dimension. `Visitor` is called as
 * visit(targetCell, sourceCell, piece) for every pair that meets.
 *
 * Both searches can be limited to the target cells [begin, end): the front
 * then stays inside that range (re-seeding where it leaves it), so disjoint
 * ranges can be searched by concurrent tasks, each with its own locator and
 * visitor, and together find exactly the pairs of the whole search.
 */
#ifndef MeshProjection_Kernel_PairSearch_h
#define MeshProjection_Kernel_PairSearch_h

#include "CandidateLocator.h"
#include "MeshView.h"

#include <algorithm>
#include <cstddef>
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
  explicit PreparedCells(const MeshView& mesh)
    : Mesh(mesh)
    , Ids(Slots, -1)
    , Valid(Slots, 0)
    , Cells(Slots)
  {
  }
  /// The prepared cell, or null for a cell of zero measure.
  const typename Intersector::Cell* Get(Index id)
  {
    const Index slot = id & (Slots - 1);
    if (this->Ids[slot] != id)
    {
      this->Ids[slot] = id;
      this->Valid[slot] = Intersector::Prepare(this->Mesh, id, this->Cells[slot]);
    }
    return this->Valid[slot] ? &this->Cells[slot] : nullptr;
  }

private:
  const MeshView& Mesh;
  std::vector<Index> Ids;
  std::vector<char> Valid;
  std::vector<typename Intersector::Cell> Cells;
};

template <class Intersector, class Visitor>
void AdvancingFrontSearch(const MeshView& target, const MeshView& source,
  CandidateLocator& locator, Visitor& visit, SearchStatistics& stats, Index begin = 0,
  Index end = -1)
{
  if (end < 0)
  {
    end = target.NumberOfCells;
  }
  using Cell = typename Intersector::Cell;
  using Piece = typename Intersector::Piece;
  constexpr int Faces = Intersector::Faces;

  struct Seed
  {
    Index Target;
    Index Source;
  };
  std::vector<char> queued(static_cast<std::size_t>(end - begin), 0); // of cell begin + i
  // stamp[s] == t: source cell s was already tried for target cell t. A
  // stamp instead of the paper's per-cell flag vector keeps the work linear.
  std::vector<Index> stamp(static_cast<std::size_t>(source.NumberOfCells), -1);
  std::vector<Seed> outer; // a binary heap: the smallest target id first
  auto later = [](const Seed& a, const Seed& b) { return a.Target > b.Target; };
  std::vector<Index> inner;
  std::vector<Index> candidates;
  Cell t;
  PreparedCells<Intersector> sources(source);
  Piece piece;
  double box[6];

  auto treat = [&](Index tId, Index seed) {
    if (!Intersector::Prepare(target, tId, t))
    {
      return; // zero measure: meets nothing (counted by the caller)
    }
    Index faceSeed[Faces];
    for (auto& f : faceSeed)
    {
      f = -1;
    }
    inner.clear();
    bool askedLocator = seed < 0;
    if (askedLocator)
    {
      Intersector::Bounds(t, box);
      locator.FindCandidates(box, candidates);
      ++stats.LocatorQueries;
      for (Index c : candidates)
      {
        stamp[c] = tId;
        inner.push_back(c);
      }
    }
    else
    {
      stamp[seed] = tId;
      inner.push_back(seed);
    }
    bool blocked = false; // the inner front met the source boundary
    bool met = false;
    for (;;)
    {
      while (!inner.empty())
      {
        const Index sId = inner.back();
        inner.pop_back();
        const Cell* prepared = sources.Get(sId);
        if (!prepared)
        {
          blocked = true; // a zero-measure source cell interrupts the walk
          continue;
        }
        const Cell& s = *prepared;
        ++stats.IntersectionTests;
        if (!Intersector::Intersect(t, s, piece))
        {
          continue;
        }
        met = true;
        ++stats.TouchingPairs;
        visit(t, s, piece);
        for (int k = 0; k < Faces; ++k)
        {
          if (piece.TouchedFaces & (1u << k))
          {
            const Index seed = Intersector::FaceSeed(piece, k, s, source);
            if (seed >= 0)
            {
              faceSeed[k] = seed;
            }
          }
        }
        // Only across the faces of s that the target reaches: any other
        // source cell meeting the target is reached through cells meeting it.
        for (int k = 0; k < Faces; ++k)
        {
          if (!(piece.SourceFaces & (1u << k)))
          {
            continue;
          }
          const Index n = source.Neighbor(sId, s.Face[k]);
          if (n < 0)
          {
            blocked = true;
          }
          else if (stamp[n] != tId)
          {
            stamp[n] = tId;
            inner.push_back(n);
          }
        }
      }
      if (askedLocator || (met && !blocked))
      {
        break;
      }
      // The seed failed or the walk hit the source boundary: the cell's
      // intersection may have parts the walk cannot reach. Ask the locator.
      askedLocator = true;
      Intersector::Bounds(t, box);
      locator.FindCandidates(box, candidates);
      ++stats.LocatorQueries;
      for (Index c : candidates)
      {
        if (stamp[c] != tId)
        {
          stamp[c] = tId;
          inner.push_back(c);
        }
      }
    }
    for (int k = 0; k < Faces; ++k)
    {
      if (faceSeed[k] < 0)
      {
        continue;
      }
      const Index n = target.Neighbor(tId, t.Face[k]);
      if (n >= begin && n < end && !queued[n - begin])
      {
        queued[n - begin] = 1;
        outer.push_back({ n, faceSeed[k] });
        std::push_heap(outer.begin(), outer.end(), later);
      }
    }
  };

  Index scan = begin;
  for (;;)
  {
    if (outer.empty())
    {
      while (scan < end && queued[scan - begin])
      {
        ++scan;
      }
      if (scan == end)
      {
        break;
      }
      queued[scan - begin] = 1;
      treat(scan, -1);
      continue;
    }
    std::pop_heap(outer.begin(), outer.end(), later);
    const Seed next = outer.back();
    outer.pop_back();
    treat(next.Target, next.Source);
  }
}

template <class Intersector, class Visitor>
void BruteForceSearch(const MeshView& target, const MeshView& source, Visitor& visit,
  SearchStatistics& stats, Index begin = 0, Index end = -1)
{
  if (end < 0)
  {
    end = target.NumberOfCells;
  }
  using Cell = typename Intersector::Cell;
  typename Intersector::Piece piece;
  std::vector<Cell> sources;
  sources.reserve(static_cast<std::size_t>(source.NumberOfCells));
  Cell c;
  for (Index sId = 0; sId < source.NumberOfCells; ++sId)
  {
    if (Intersector::Prepare(source, sId, c))
    {
      sources.push_back(c);
    }
  }
  Cell t;
  for (Index tId = begin; tId < end; ++tId)
  {
    if (!Intersector::Prepare(target, tId, t))
    {
      continue;
    }
    for (const Cell& s : sources)
    {
      ++stats.IntersectionTests;
      if (Intersector::Intersect(t, s, piece))
      {
        ++stats.TouchingPairs;
        visit(t, s, piece);
      }
    }
  }
}
} // namespace mp

#endif
