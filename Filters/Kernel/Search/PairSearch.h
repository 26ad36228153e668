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
 *    In the plane a cell outside needs none: the winding number of the
 *    boundary faces about one of its corners, zero on a source without
 *    folds, proves that corner, and so the cell, outside
 *    (CandidateLocator::Outside; layers that overlap count twice there).
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
#include "Search/SourceWalk.h"

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
{};
template <class Intersector, class Sources>
struct HasApart<Intersector, Sources,
  std::enable_if_t<std::is_same<typename Intersector::Cell, typename Sources::Cell>::value,
    decltype(void(Intersector::Apart(std::declval<const typename Intersector::Cell&>(),
      std::declval<const typename Intersector::Cell&>())))>> : std::true_type
{};

/// Whether the intersector's cells meet only in positive volume
/// (tetrahedra), so that a boundary face supporting the source
/// (CandidateLocator::Supports) cannot cut a target cell's cover apart.
template <class Intersector, class = void>
struct MeetsInVolume : std::false_type
{};
template <class Intersector>
struct MeetsInVolume<Intersector, std::enable_if_t<Intersector::MeetsInVolume>> : std::true_type
{};

/**
 * The advancing front's state over target cells [begin, end): the outer
 * front (a heap of target cells with their seeds), the inner front of the
 * target cell treated, and what walks and queries have cost so far (see
 * the file comment, which the steps below follow). AdvancingFrontSearch
 * runs one per range.
 */
template <class Intersector, class Visitor>
class AdvancingFront
{
public:
  AdvancingFront(const MeshView& target, const MeshView& source, CandidateLocator& locator,
    Visitor& visit, SearchStatistics& stats, Index begin, Index end,
    std::vector<Index>* degenerateSources)
    : Target(target)
    , Source(source)
    , Locator(locator)
    , Visit(visit)
    , Stats(stats)
    , Begin(begin)
    , End(end)
    , Queued(static_cast<size_t>(std::max<Index>(0, end - begin)), 0)
    , Stamp(static_cast<std::size_t>(source.NumberOfCells), -1)
    , Prepared(source, degenerateSources)
    , Starts(source)
    , StartSamples(WalkStarts::Samples(source.NumberOfCells))
  {
    // Where walks start: the last source cell met, at first the source cell
    // at the same relative position as the range (meshes stored with some
    // locality then need short walks).
    if (source.NumberOfCells > 0 && target.NumberOfCells > 0)
    {
      this->LastMet = static_cast<Index>(static_cast<double>(begin) / target.NumberOfCells *
        static_cast<double>(source.NumberOfCells));
      this->LastMet = std::min(std::max<Index>(this->LastMet, 0), source.NumberOfCells - 1);
    }
    // A straight walk crosses about n^(1/d) cells of a mesh of n cells.
    this->MaxWalk = 100 +
      4 *
        static_cast<Index>(
          std::pow(static_cast<double>(source.NumberOfCells), 1.0 / Sources::Dimension));
  }

  /// Treats every target cell of the range once: those the outer front
  /// reached first, smallest id first, then the next one not reached yet.
  /// Returns early when `poll` says so.
  void Run(const std::function<bool(Index done)>& poll)
  {
    Index scan = this->Begin;
    for (Index done = 0;; ++done)
    {
      // Progress, and a way out, every ProgressChunk target cells.
      if (poll && done > 0 && done % ProgressChunk == 0 && !poll(done))
      {
        return;
      }
      if (this->Outer.empty())
      {
        while (scan < this->End && this->Queued[scan - this->Begin])
        {
          ++scan;
        }
        if (scan == this->End)
        {
          break;
        }
        this->Queued[scan - this->Begin] = 1;
        this->Treat(scan, -1);
        continue;
      }
      std::pop_heap(this->Outer.begin(), this->Outer.end(), Later);
      const Seed next = this->Outer.back();
      this->Outer.pop_back();
      this->Treat(next.Target, next.Source);
    }
  }

private:
  using Cell = typename Intersector::Cell;
  using Piece = typename Intersector::Piece;
  static constexpr int Faces = Intersector::Faces;
  // The source cells' own geometry (a volume's, for traces: SourceSide.h).
  using Sources = typename SourceSideOf<Intersector>::type;
  using SourceCell = typename Sources::Cell;
  static constexpr int SourceFaces = Sources::Faces;

  struct Seed
  {
    Index Target;
    Index Source;
  };
  /// The heap's order: the smallest target id on top.
  static bool Later(const Seed& a, const Seed& b) { return a.Target > b.Target; }

  /// What the inner front of the target cell treated has found so far.
  struct InnerState
  {
    Index FaceSeed[Faces]; ///< per target face, a source cell meeting it (-1: none yet)
    bool Walked = false;   ///< a walk was tried for this cell
    /// What the inner front started from: 0 the seed, 1 also the boundary
    /// cells nearby, 2 all source cells nearby.
    int Level = 0;
    bool Blocked = false; ///< the inner front met the source boundary
    /// A surface's source facet near the cell was screened out (normals,
    /// reach): the facets meeting the cell may not be connected through
    /// each other, so only a query among all source cells nearby is sure.
    bool Screened = false;
    bool Met = false;
    bool Degenerate = false; ///< a source cell of zero measure was on the inner front
    InnerState()
    {
      for (auto& f : this->FaceSeed)
      {
        f = -1;
      }
    }
    /// Nothing can be missing: all cells asked, or the boundary cells asked
    /// after something was met, or met without the boundary.
    bool Complete() const
    {
      return this->Level == 2 ||
        (this->Met && !this->Screened && (this->Level == 1 || !this->Blocked));
    }
  };

  /// Walks are for the few cells that start a front. Where there are many
  /// (a target of many disconnected pieces, e.g. cells that share no
  /// points), their steps stay within this budget, then the locator takes
  /// over: the search stays linear.
  Index WalkBudget() const { return 16 * this->Treated + 64 * this->MaxWalk; }

  /// Source cell n joins target cell tId's inner front, unless it was tried already.
  void Reach(Index tId, Index n)
  {
    if (this->Stamp[n] != tId)
    {
      this->Stamp[n] = tId;
      this->Inner.push_back(n);
    }
  }

  /// One target cell: its seed (or the locator), its inner front until
  /// nothing can be missing, then its neighbours onto the outer front.
  void Treat(Index tId, Index seed)
  {
    if (!Intersector::Prepare(this->Target, tId, this->T))
    {
      ++this->Stats.DegenerateTargetCells; // zero measure: meets nothing
      return;
    }
    InnerState state;
    this->Inner.clear();
    ++this->Treated;
    if (seed < 0)
    {
      seed = this->Walk(state, this->LastMet);
    }
    if (seed >= 0)
    {
      this->Stamp[seed] = static_cast<NeighborId>(tId);
      this->Inner.push_back(seed);
    }
    else
    {
      state.Level = this->AskedAll ? 2 : 1;
      this->Ask(tId, state.Level == 2);
    }
    for (;;)
    {
      this->Advance(tId, state);
      if (state.Complete())
      {
        break;
      }
      // A seed from the front that does not meet the cell (3D seeds rest on
      // face contacts above a rounding threshold) is near it: a short walk
      // from it finds a cell that does, without a query.
      if (!state.Met && state.Level == 0 && !state.Walked)
      {
        const Index found = this->Walk(state, seed);
        if (found >= 0 && this->Stamp[found] != tId)
        {
          this->Stamp[found] = tId;
          this->Inner.push_back(found);
          continue;
        }
      }
      // Not even a boundary cell nearby meets the cell: it lies wholly
      // inside the source or wholly outside it. A corner outside settles
      // it (met nothing) without the query among all source cells.
      if (state.Level == 1 && !state.Met && !state.Screened && !state.Degenerate &&
        this->CornerOutside(tId))
      {
        ++this->Stats.OutsideCells;
        break;
      }
      // The seed failed, or the walk ran into the source boundary: ask for
      // the boundary cells nearby; if still nothing meets the cell, for all.
      state.Level = (state.Met || (state.Level == 0 && !this->AskedAll)) && !state.Screened ? 1 : 2;
      this->Ask(tId, state.Level == 2);
    }
    this->QueueNeighbours(tId, state);
  }

  /// A walk toward the treated cell's center, from `from`: a source cell
  /// holding it, or -1 (also when walks are off: after a query among all
  /// cells, or beyond their budget).
  Index Walk(InnerState& state, Index from)
  {
    state.Walked = true;
    SearchStatistics& stats = this->Stats;
    if (this->AskedAll || from < 0 || stats.WalkSteps >= this->WalkBudget())
    {
      return -1;
    }
    double q[3] = { 0.0, 0.0, 0.0 };
    Intersector::Center(this->T, q);
    ++stats.SeedWalks;
    const Index found =
      WalkToward<Sources>(this->Source, this->Prepared, from, q, this->MaxWalk, stats.WalkSteps);
    // Stopped on the way (a hole of the source, a cell of zero measure): once more,
    // from the sampled cell nearest the center. Each look-up scans the
    // samples: allowed while they add up to at most 16 per treated cell
    // and 64 scans, so that the search stays linear.
    const Index scans = this->Restarts + 1;
    if (found >= 0 || stats.WalkSteps >= this->WalkBudget() ||
      scans * this->StartSamples > 16 * this->Treated + 64 * this->StartSamples)
    {
      return found;
    }
    this->Restarts = scans;
    const Index near = this->Starts.Nearest(q);
    if (near < 0 || near == from)
    {
      return -1;
    }
    ++stats.WalkRestarts;
    return WalkToward<Sources>(
      this->Source, this->Prepared, near, q, this->MaxWalk, stats.WalkSteps);
  }

  /// Whether the locator proves a corner of target cell tId outside the
  /// source (CandidateLocator::Outside; triangles of a plane only).
  bool CornerOutside(Index tId) const
  {
    if constexpr (Intersector::Dimension == 2 && std::is_same<Cell, SourceCell>::value)
    {
      if (this->Target.CellDimension == 2 && this->Target.SpaceDimension == 2)
      {
        return this->Locator.Outside(this->Target.Point(this->Target.Cell(tId)[0]));
      }
    }
    return false;
  }

  /// Adds the locator's candidates (boundary cells, or all cells) to the inner front.
  void Ask(Index tId, bool all)
  {
    Intersector::Bounds(this->T, this->Box);
    if (all)
    {
      this->Locator.FindCandidates(this->Box, this->Candidates);
      ++this->Stats.FullLocatorQueries;
      this->AskedAll = true;
    }
    else
    {
      this->Locator.FindBoundaryCandidates(this->Box, this->Candidates);
    }
    ++this->Stats.LocatorQueries;
    for (Index c : this->Candidates)
    {
      if (this->Stamp[c] != static_cast<NeighborId>(tId))
      {
        this->Stamp[c] = static_cast<NeighborId>(tId);
        // Most candidates miss: a cheap screen first where the geometry
        // has one (tetrahedra), counted as the test it settles.
        if constexpr (HasApart<Intersector, Sources>::value)
        {
          const SourceCell* cell = this->Prepared.Get(c);
          if (cell && Intersector::Apart(this->T, *cell))
          {
            ++this->Stats.IntersectionTests;
            continue;
          }
        }
        this->Inner.push_back(c);
      }
    }
  }

  /// Runs the inner front until it is empty: every source cell on it is
  /// intersected with the treated cell, and those that meet it pass the
  /// front on.
  void Advance(Index tId, InnerState& state)
  {
    while (!this->Inner.empty())
    {
      const Index sId = this->Inner.back();
      this->Inner.pop_back();
      const SourceCell* prepared = this->Prepared.Get(sId);
      if (!prepared)
      {
        // Zero measure: meets nothing, but must not cut the walk off from
        // the cells beyond it.
        state.Degenerate = true;
        for (int k = 0; k < SourceFaces; ++k)
        {
          const Index n = this->Source.Neighbor(sId, k);
          if (n < 0)
          {
            state.Blocked = true;
          }
          else
          {
            this->Reach(tId, n);
          }
        }
        continue;
      }
      const SourceCell& s = *prepared;
      ++this->Stats.IntersectionTests;
      if (!Intersector::Intersect(this->T, s, this->P))
      {
        state.Screened = state.Screened || Intersector::Screened(this->P);
        continue;
      }
      this->Meet(tId, sId, s, state);
    }
  }

  /// Source cell sId meets the treated cell: the pair is visited, the
  /// source cells met across the target's faces become those neighbours'
  /// seeds, and the front goes on across the source faces the piece reaches.
  void Meet(Index tId, Index sId, const SourceCell& s, InnerState& state)
  {
    Piece& piece = this->P;
    state.Met = true;
    this->LastMet = sId;
    ++this->Stats.TouchingPairs;
    this->Visit(this->T, s, piece);
    // The faces' bits visited lowest first (a test per face depends on
    // the data and was often mispredicted): the same order.
    for (unsigned touched = piece.TouchedFaces & ((1u << Faces) - 1u); touched != 0;
         touched &= touched - 1)
    {
      const int k = __builtin_ctz(touched);
      const Index next = Intersector::FaceSeed(piece, k, s, this->Source);
      if (next >= 0)
      {
        state.FaceSeed[k] = next;
      }
    }
    // Its boundary faces that support the source are trusted (no query)
    // only when the piece is far above rounding: a sliver where the
    // cells nearly only touch can have faces that its neighbours,
    // tested on their own, do not confirm.
    bool trusted = false;
    if constexpr (MeetsInVolume<Intersector>::value)
    {
      trusted = Intersector::Substantial(this->T, s, piece);
    }
    // Only across the faces of s that the target reaches: any other
    // source cell meeting the target is reached through cells meeting it.
    for (unsigned reached = piece.SourceFaces & ((1u << SourceFaces) - 1u); reached != 0;
         reached &= reached - 1)
    {
      const int k = __builtin_ctz(reached);
      const Index n = this->Source.Neighbor(sId, s.Face[k]);
      if (n < 0)
      {
        // A boundary face with the whole source on the cell's side
        // bounds the cover without cutting it apart: no query for it.
        state.Blocked = state.Blocked || !trusted || !this->Locator.Supports(sId, s.Face[k]);
      }
      else
      {
        this->Reach(tId, n);
      }
    }
  }

  /// The treated cell's neighbours in the range, not queued yet, join the
  /// outer front with the seeds its faces found.
  void QueueNeighbours(Index tId, const InnerState& state)
  {
    for (int k = 0; k < Faces; ++k)
    {
      if (state.FaceSeed[k] < 0)
      {
        continue;
      }
      const Index n = this->Target.Neighbor(tId, this->T.Face[k]);
      if (n >= this->Begin && n < this->End && !this->Queued[n - this->Begin])
      {
        this->Queued[n - this->Begin] = 1;
        this->Outer.push_back({ n, state.FaceSeed[k] });
        std::push_heap(this->Outer.begin(), this->Outer.end(), Later);
      }
    }
  }

  const MeshView& Target;
  const MeshView& Source;
  CandidateLocator& Locator;
  Visitor& Visit;
  SearchStatistics& Stats;
  const Index Begin;
  const Index End;
  LargeVector<char> Queued; ///< of cell Begin + i
  // Stamp[s] == t: source cell s was already tried for target cell t. A
  // stamp instead of the paper's per-cell flag vector keeps the work linear.
  // (32 bits: the front's meshes have fewer than 2^31 cells, MeshView.h.)
  LargeVector<NeighborId> Stamp;
  std::vector<Seed> Outer; ///< a binary heap: the smallest target id first
  std::vector<Index> Inner;
  std::vector<Index> Candidates;
  Cell T; ///< the target cell treated
  PreparedCells<Sources> Prepared;
  Piece P;
  double Box[6];
  Index LastMet = -1;
  Index MaxWalk = 0;
  WalkStarts Starts;
  const Index StartSamples;
  Index Restarts = 0;    ///< walks started again from a sample
  bool AskedAll = false; ///< a query among all source cells was made: no more walks
  Index Treated = 0;
};

/**
 * The advancing front over target cells [begin, end) (all by default).
 * Target cells of zero measure are counted in `stats`; source cells of zero
 * measure that the front meets go to `degenerateSources` when given (ids,
 * possibly repeated).
 */
template <class Intersector, class Visitor>
void AdvancingFrontSearch(const MeshView& target, const MeshView& source, CandidateLocator& locator,
  Visitor& visit, SearchStatistics& stats, Index begin = 0, Index end = -1,
  std::vector<Index>* degenerateSources = nullptr,
  const std::function<bool(Index done)>& poll = nullptr)
{
  if (end < 0)
  {
    end = target.NumberOfCells;
  }
  AdvancingFront<Intersector, Visitor> front(
    target, source, locator, visit, stats, begin, end, degenerateSources);
  front.Run(poll);
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
