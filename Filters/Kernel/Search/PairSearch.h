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
 * the other mesh is connected. A target cell the front has not reached
 * (the first one, and the first of every part the front cannot reach) gets
 * its seed from a walk through the source mesh toward its center, from the
 * last source cell met (a visibility walk: always into the neighbour across a
 * face that has the point strictly beyond it; a bounded number of steps);
 * where a hole of the source on the way stops it, a second walk from the
 * nearest of a sample of source cells (WalkStarts).
 * Where there is no seed, where the seed does not meet the cell, or where the
 * inner front runs into the source boundary (there the cell's intersection
 * may be disconnected; in 3D not when every boundary face it ran into
 * supports the source, Search/SupportingFaces.h), the locator is asked, in
 * two steps:
 *  - first for the source cells *at the boundary* near the cell. That is
 *    enough whenever the cell meets the source boundary: every group of
 *    source cells meeting the cell that the inner front cannot reach from
 *    the others leaves part of the cell uncovered, so its own walk over the
 *    cell would run into the source boundary, i.e. it contains a boundary
 *    cell meeting the cell (unless it covers the whole cell: a source that
 *    overlaps itself, which no search here takes apart);
 *  - only when that meets nothing either (the cell lies inside the source
 *    away from its boundary, or outside it) among all source cells. After
 *    the first such query, unseeded cells go straight to it (no more walks).
 * So on meshes of the same domain the front needs one walk per range and a
 * few boundary queries, and never an index over all source cells. Source
 * cells of zero measure do not stop the inner front: it passes through
 * them to all their neighbours.
 *
 * Meeting is decided with exact predicates (in 2D on closed cells, so cells
 * that only touch in a vertex or along an edge keep the fronts going; in 3D
 * by positive volume, with seeds through shared faces), and both searches
 * find exactly the same pairs.
 *
 * `Intersector` is the cell-pair geometry (TriangleIntersector in 2D); the
 * search itself does not depend on the dimension. The source cells may be
 * of another kind than the target's (traces: a surface or curve in a volume
 * mesh): they are prepared, walked and counted by face with the
 * intersector's SourceSide (Geometry/SourceSide.h). `Visitor` is called as
 * visit(targetCell, sourceCell, piece) for every pair that meets.
 *
 * Both searches can be limited to the target cells [begin, end): the front
 * then stays inside that range (re-seeding where it leaves it), so disjoint
 * ranges can be searched by concurrent tasks, each with its own locator and
 * visitor, and together find exactly the pairs of the whole search.
 */
#ifndef MeshProjection_Kernel_PairSearch_h
#define MeshProjection_Kernel_PairSearch_h

#include "Geometry/SourceSide.h"
#include "Search/CandidateLocator.h"
#include "Mesh/LargeArray.h"
#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"
#include "Search/SearchStatistics.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <type_traits>
#include <utility>
#include <cmath>
#include <cstddef>
#include <vector>

namespace mp
{
/// Whether the intersector screens candidates with Apart(target, source)
/// (cells of one kind only).
template <class Intersector, class Sources, class = void>
struct HasApart : std::false_type
{
};
template <class Intersector, class Sources>
struct HasApart<Intersector, Sources,
  std::enable_if_t<std::is_same<typename Intersector::Cell, typename Sources::Cell>::value,
    decltype(void(Intersector::Apart(std::declval<const typename Intersector::Cell&>(),
      std::declval<const typename Intersector::Cell&>())))>> : std::true_type
{
};

/// Whether the intersector's cells meet only in positive volume
/// (tetrahedra), so that a boundary face supporting the source
/// (CandidateLocator::Supports) cannot cut a target cell's cover apart.
template <class Intersector, class = void>
struct MeetsInVolume : std::false_type
{
};
template <class Intersector>
struct MeetsInVolume<Intersector, std::enable_if_t<Intersector::MeetsInVolume>> : std::true_type
{
};

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
  {
  }
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
 * Walks from source cell `start` toward point q (see the file comment): the
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

/**
 * The advancing front over target cells [begin, end) (all by default).
 * Target cells of zero measure are counted in `stats`; source cells of zero
 * measure that the front meets go to `degenerateSources` when given (ids,
 * possibly repeated).
 */
template <class Intersector, class Visitor>
void AdvancingFrontSearch(const MeshView& target, const MeshView& source,
  CandidateLocator& locator, Visitor& visit, SearchStatistics& stats, Index begin = 0,
  Index end = -1, std::vector<Index>* degenerateSources = nullptr,
  const std::function<bool(Index done)>& poll = nullptr)
{
  if (end < 0)
  {
    end = target.NumberOfCells;
  }
  using Cell = typename Intersector::Cell;
  using Piece = typename Intersector::Piece;
  constexpr int Faces = Intersector::Faces;
  // The source cells' own geometry (a volume's, for traces: SourceSide.h).
  using Sources = typename SourceSideOf<Intersector>::type;
  using SourceCell = typename Sources::Cell;
  constexpr int SourceFaces = Sources::Faces;

  struct Seed
  {
    Index Target;
    Index Source;
  };
  LargeVector<char> queued(static_cast<size_t>(std::max<Index>(0, end - begin)), 0); // of cell begin + i
  // stamp[s] == t: source cell s was already tried for target cell t. A
  // stamp instead of the paper's per-cell flag vector keeps the work linear.
  // (32 bits: the front's meshes have fewer than 2^31 cells, MeshView.h.)
  LargeVector<NeighborId> stamp(static_cast<std::size_t>(source.NumberOfCells), -1);
  std::vector<Seed> outer; // a binary heap: the smallest target id first
  auto later = [](const Seed& a, const Seed& b) { return a.Target > b.Target; };
  std::vector<Index> inner;
  std::vector<Index> candidates;
  Cell t;
  PreparedCells<Sources> sources(source, degenerateSources);
  Piece piece;
  double box[6];
  // Where walks start: the last source cell met, at first the source cell
  // at the same relative position as the range (meshes stored with some
  // locality then need short walks).
  Index lastMet = -1;
  if (source.NumberOfCells > 0 && target.NumberOfCells > 0)
  {
    lastMet = static_cast<Index>(static_cast<double>(begin) / target.NumberOfCells *
      static_cast<double>(source.NumberOfCells));
    lastMet = std::min(std::max<Index>(lastMet, 0), source.NumberOfCells - 1);
  }
  // A straight walk crosses about n^(1/d) cells of a mesh of n cells.
  const Index maxWalk = 100 +
    4 * static_cast<Index>(std::pow(
          static_cast<double>(source.NumberOfCells), 1.0 / Sources::Dimension));
  WalkStarts starts(source);
  const Index startSamples = WalkStarts::Samples(source.NumberOfCells);
  Index restarts = 0; // walks started again from a sample
  bool askedAll = false; // a query among all source cells was made: no more walks
  // Walks are for the few cells that start a front. Where there are many
  // (a target of many disconnected pieces, e.g. cells that share no
  // points), their steps stay within this budget, then the locator takes
  // over: the search stays linear.
  Index treated = 0;
  auto walkBudget = [&] { return 16 * treated + 64 * maxWalk; };

  // Adds the locator's candidates (boundary cells, or all cells) to the inner front.
  auto ask = [&](Index tId, bool all) {
    Intersector::Bounds(t, box);
    if (all)
    {
      locator.FindCandidates(box, candidates);
      ++stats.FullLocatorQueries;
      askedAll = true;
    }
    else
    {
      locator.FindBoundaryCandidates(box, candidates);
    }
    ++stats.LocatorQueries;
    for (Index c : candidates)
    {
      if (stamp[c] != static_cast<NeighborId>(tId))
      {
        stamp[c] = static_cast<NeighborId>(tId);
        // Most candidates miss: a cheap screen first where the geometry
        // has one (tetrahedra), counted as the test it settles.
        if constexpr (HasApart<Intersector, Sources>::value)
        {
          const SourceCell* cell = sources.Get(c);
          if (cell && Intersector::Apart(t, *cell))
          {
            ++stats.IntersectionTests;
            continue;
          }
        }
        inner.push_back(c);
      }
    }
  };

  auto treat = [&](Index tId, Index seed) {
    if (!Intersector::Prepare(target, tId, t))
    {
      ++stats.DegenerateTargetCells; // zero measure: meets nothing
      return;
    }
    Index faceSeed[Faces];
    for (auto& f : faceSeed)
    {
      f = -1;
    }
    inner.clear();
    ++treated;
    // A walk toward the cell's center, from `from`: a source cell holding
    // it, or -1 (also when walks are off: after a query among all cells, or
    // beyond their budget).
    bool walked = false;
    auto walk = [&](Index from) -> Index {
      walked = true;
      if (askedAll || from < 0 || stats.WalkSteps >= walkBudget())
      {
        return -1;
      }
      double q[3] = { 0.0, 0.0, 0.0 };
      Intersector::Center(t, q);
      ++stats.SeedWalks;
      const Index found = WalkToward<Sources>(source, sources, from, q, maxWalk, stats.WalkSteps);
      // Stopped on the way (a hole of the source, a cell of zero measure): once more,
      // from the sampled cell nearest the center. Each look-up scans the
      // samples: allowed while they add up to at most 16 per treated cell
      // and 64 scans, so that the search stays linear.
      const Index scans = restarts + 1;
      if (found >= 0 || stats.WalkSteps >= walkBudget() ||
        scans * startSamples > 16 * treated + 64 * startSamples)
      {
        return found;
      }
      restarts = scans;
      const Index near = starts.Nearest(q);
      if (near < 0 || near == from)
      {
        return -1;
      }
      ++stats.WalkRestarts;
      return WalkToward<Sources>(source, sources, near, q, maxWalk, stats.WalkSteps);
    };
    if (seed < 0)
    {
      seed = walk(lastMet);
    }
    // What the inner front started from: 0 the seed, 1 also the boundary
    // cells nearby, 2 all source cells nearby.
    int level = 0;
    if (seed >= 0)
    {
      stamp[seed] = static_cast<NeighborId>(tId);
      inner.push_back(seed);
    }
    else
    {
      level = askedAll ? 2 : 1;
      ask(tId, level == 2);
    }
    bool blocked = false; // the inner front met the source boundary
    // A surface's source facet near the cell was screened out (normals,
    // reach): the facets meeting the cell may not be connected through
    // each other, so only a query among all source cells nearby is sure.
    bool screened = false;
    bool met = false;
    for (;;)
    {
      while (!inner.empty())
      {
        const Index sId = inner.back();
        inner.pop_back();
        const SourceCell* prepared = sources.Get(sId);
        if (!prepared)
        {
          // Zero measure: meets nothing, but must not cut the walk off from
          // the cells beyond it.
          for (int k = 0; k < SourceFaces; ++k)
          {
            const Index n = source.Neighbor(sId, k);
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
          continue;
        }
        const SourceCell& s = *prepared;
        ++stats.IntersectionTests;
        if (!Intersector::Intersect(t, s, piece))
        {
          screened = screened || Intersector::Screened(piece);
          continue;
        }
        met = true;
        lastMet = sId;
        ++stats.TouchingPairs;
        visit(t, s, piece);
        // The faces' bits visited lowest first (a test per face depends on
        // the data and was often mispredicted): the same order.
        for (unsigned touched = piece.TouchedFaces & ((1u << Faces) - 1u); touched != 0; touched &= touched - 1)
        {
          const int k = __builtin_ctz(touched);
          const Index next = Intersector::FaceSeed(piece, k, s, source);
          if (next >= 0)
          {
            faceSeed[k] = next;
          }
        }
        // Its boundary faces that support the source are trusted (no query)
        // only when the piece is far above rounding: a sliver where the
        // cells nearly only touch can have faces that its neighbours,
        // tested on their own, do not confirm.
        bool trusted = false;
        if constexpr (MeetsInVolume<Intersector>::value)
        {
          trusted = Intersector::Substantial(t, s, piece);
        }
        // Only across the faces of s that the target reaches: any other
        // source cell meeting the target is reached through cells meeting it.
        for (unsigned reached = piece.SourceFaces & ((1u << SourceFaces) - 1u); reached != 0; reached &= reached - 1)
        {
          const int k = __builtin_ctz(reached);
          const Index n = source.Neighbor(sId, s.Face[k]);
          if (n < 0)
          {
            // A boundary face with the whole source on the cell's side
            // bounds the cover without cutting it apart: no query for it.
            blocked = blocked || !trusted || !locator.Supports(sId, s.Face[k]);
          }
          else if (stamp[n] != tId)
          {
            stamp[n] = tId;
            inner.push_back(n);
          }
        }
      }
      // Done when nothing can be missing: all cells asked, or the boundary
      // cells asked after something was met, or met without the boundary.
      if (level == 2 || (met && !screened && (level == 1 || !blocked)))
      {
        break;
      }
      // A seed from the front that does not meet the cell (3D seeds rest on
      // face contacts above a rounding threshold) is near it: a short walk
      // from it finds a cell that does, without a query.
      if (!met && level == 0 && !walked)
      {
        const Index found = walk(seed);
        if (found >= 0 && stamp[found] != tId)
        {
          stamp[found] = tId;
          inner.push_back(found);
          continue;
        }
      }
      // The seed failed, or the walk ran into the source boundary: ask for
      // the boundary cells nearby; if still nothing meets the cell, for all.
      level = (met || (level == 0 && !askedAll)) && !screened ? 1 : 2;
      ask(tId, level == 2);
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
  for (Index done = 0;; ++done)
  {
    // Progress, and a way out, every ProgressChunk target cells.
    if (poll && done > 0 && done % ProgressChunk == 0 && !poll(done))
    {
      return;
    }
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

/// Every target cell of [begin, end) against every source cell; counts as
/// AdvancingFrontSearch (every source cell of zero measure).
template <class Intersector, class Visitor>
void BruteForceSearch(const MeshView& target, const MeshView& source, Visitor& visit,
  SearchStatistics& stats, Index begin = 0, Index end = -1,
  std::vector<Index>* degenerateSources = nullptr,
  const std::function<bool(Index done)>& poll = nullptr)
{
  if (end < 0)
  {
    end = target.NumberOfCells;
  }
  using Cell = typename Intersector::Cell;
  using Sources = typename SourceSideOf<Intersector>::type;
  using SourceCell = typename Sources::Cell;
  typename Intersector::Piece piece;
  std::vector<SourceCell> sources;
  sources.reserve(static_cast<std::size_t>(source.NumberOfCells));
  SourceCell c;
  for (Index sId = 0; sId < source.NumberOfCells; ++sId)
  {
    if (Sources::Prepare(source, sId, c))
    {
      sources.push_back(c);
    }
    else if (degenerateSources)
    {
      degenerateSources->push_back(sId);
    }
  }
  Cell t;
  for (Index tId = begin; tId < end; ++tId)
  {
    if (poll && tId > begin && (tId - begin) % 64 == 0 && !poll(tId - begin))
    {
      return;
    }
    if (!Intersector::Prepare(target, tId, t))
    {
      ++stats.DegenerateTargetCells;
      continue;
    }
    for (const SourceCell& s : sources)
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
