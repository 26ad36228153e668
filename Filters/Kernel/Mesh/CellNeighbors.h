// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CellNeighbors.h
 * @brief Face neighbours of a simplicial mesh, without VTK.
 *
 * BuildFaceNeighbors, for every caller (the filter, the tests, the
 * benchmark): the kernel's own point-to-cell lists (a counting sort), and
 * each face matched at its lowest point (MatchFacesAtPoints); MatchFaces,
 * face by face among the cells around its first corner, where a cell names
 * a point twice. Linear time. A face shared by more than two cells (a
 * non-manifold mesh) gets no neighbour, and their number is returned.
 */
#ifndef MeshProjection_Kernel_CellNeighbors_h
#define MeshProjection_Kernel_CellNeighbors_h

#include "Mesh/LargeArray.h"
#include "Mesh/MeshView.h"
#include "Mesh/SortEight.h"
#include "Mesh/Tasks.h"

#include <algorithm>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mp
{
/**
 * Matches the faces of cells [begin, end) of `mesh` (segments, triangles or
 * tetrahedra): neighbors[c * corners + k] becomes the cell across face k of
 * c, where exactly one other cell holds all the face's corners. Entries
 * already set (>= 0) are kept: a face found from its other side is not
 * matched again, and the neighbour's own entry is written when the
 * neighbour lies in [begin, end) too (so that concurrent ranges never write
 * the same entry). around(p, visit) calls visit(cell) for every cell of the
 * mesh (kernel ids) using point p. Returns how many faces, seen from a cell
 * of the range, are shared by more than two cells.
 */
template <int Corners, class Around>
Index MatchFacesOf(
  const MeshView& mesh, const Around& around, NeighborId* neighbors, Index begin, Index end)
{
  constexpr int corners = Corners;
  Index nonManifold = 0;
  for (Index c = begin; c < end; ++c)
  {
    const CellCorners ids = mesh.Cell(c);
    for (int k = 0; k < corners; ++k)
    {
      if (neighbors[c * corners + k] >= 0)
      {
        continue; // found from the other side
      }
      // The face's corners: first, and up to two more (a segment's face is
      // one point, a triangle's two, a tetrahedron's three).
      const Index first = ids[(k + 1) % corners];
      const Index second = corners > 2 ? ids[(k + 2) % corners] : first;
      const Index third = corners > 3 ? ids[(k + 3) % corners] : second;
      Index found = -1;
      int matches = 0;
      around(first, [&](Index other) {
        const CellCorners o = mesh.Cell(other);
        bool shares = false;
        bool shares3 = false;
        for (int l = 0; l < corners; ++l)
        {
          shares |= o[l] == second;
          shares3 |= o[l] == third;
        }
        if (shares & shares3 & (other != c))
        {
          found = other;
          ++matches;
        }
      });
      if (matches == 1)
      {
        neighbors[c * corners + k] = static_cast<NeighborId>(found);
        // The same face seen from the neighbour: the corner of `found` that
        // is not on it.
        if (found >= begin && found < end)
        {
          const CellCorners o = mesh.Cell(found);
          for (int l = 0; l < corners; ++l)
          {
            if (o[l] != first && o[l] != second && o[l] != third)
            {
              neighbors[found * corners + l] = static_cast<NeighborId>(c);
            }
          }
        }
      }
      else if (matches > 1)
      {
        ++nonManifold;
      }
    }
  }
  return nonManifold;
}

template <class Around>
Index MatchFaces(
  const MeshView& mesh, const Around& around, NeighborId* neighbors, Index begin, Index end)
{
  switch (mesh.CornersPerCell())
  {
    case 2:
      return MatchFacesOf<2>(mesh, around, neighbors, begin, end);
    case 3:
      return MatchFacesOf<3>(mesh, around, neighbors, begin, end);
    default:
      return MatchFacesOf<4>(mesh, around, neighbors, begin, end);
  }
}

/**
 * The corners of a simplex's face opposite corner k other than corner `at`
 * (the face's point being matched), in increasing order: one for a
 * triangle (key1 stays -1), two for a tetrahedron (from a table: a loop
 * testing each corner was mispredicted).
 */
template <int Corners>
inline void FaceOtherCorners(const CellCorners& ids, int k, int at, Index& key0, Index& key1)
{
  if constexpr (Corners == 3)
  {
    key0 = ids[3 - k - at];
  }
  else if constexpr (Corners == 4)
  {
    static constexpr signed char others[4][4][2] = {
      { { -1, -1 }, { 2, 3 }, { 1, 3 }, { 1, 2 } },
      { { 2, 3 }, { -1, -1 }, { 0, 3 }, { 0, 2 } },
      { { 1, 3 }, { 0, 3 }, { -1, -1 }, { 0, 1 } },
      { { 1, 2 }, { 0, 2 }, { 0, 1 }, { -1, -1 } },
    };
    key0 = ids[others[k][at][0]];
    key1 = ids[others[k][at][1]];
  }
  if (key1 >= 0 && key1 < key0)
  {
    std::swap(key0, key1);
  }
}

/// Two cells sharing a face (f and g: a cell and the side it has the face on) are each other's neighbours.
template <int Corners, class Face>
inline void PairFaces(const Face& f, const Face& g, NeighborId* neighbors)
{
  neighbors[f.Cell * Corners + f.Side] = static_cast<NeighborId>(g.Cell);
  neighbors[g.Cell * Corners + g.Side] = static_cast<NeighborId>(f.Cell);
}

/**
 * Matches faces at their lowest point: for each point p of [begin, end),
 * the faces of the cells around p (start, around: BuildPointCells) whose
 * other corners all have higher ids, grouped by those corners. A group of
 * two cells are each other's neighbours (both entries written); a face of
 * more than two cells gets none, and adds its number of cells to the count
 * returned (so half the sum over all points is MatchFaces' count halved:
 * the number of non-manifold faces when each is shared by three cells).
 * Every face is matched at one point only, so concurrent ranges of points
 * never write the same entry. Entries of faces without a partner are left
 * as they are (-1). Cells naming a point twice are not matched alike by
 * MatchFaces: returns -1 when one is around a point of the range (the
 * caller then matches with MatchFaces). The mesh must have fewer than
 * 2^32 - 1 points (a face's two other corners are one 64-bit key).
 *
 * Faster than MatchFaces: each cell's corners are read once per corner,
 * not once per face and cell around the face's first corner. The faces
 * through a point are sorted to be grouped: n log n in their number, also
 * around the centre of a fan.
 */
template <int Corners, class Id>
Index MatchFacesAtPoints(const MeshView& mesh, const Id* start, const Id* around,
  NeighborId* neighbors, Index begin, Index end)
{
  // The face's other corners, increasing (unused: -1), packed into one
  // 64-bit key (the caller checks that the mesh has fewer than 2^32 - 1
  // points): one comparison per step of the sort instead of two.
  struct Face
  {
    unsigned long long Key;
    Index Cell;
    int Side;
    bool operator<(const Face& o) const { return this->Key < o.Key; }
    bool Same(const Face& o) const { return this->Key == o.Key; }
  };
  auto pack = [](Index key0, Index key1) {
    return (static_cast<unsigned long long>(key0 + 1) << 32) |
      static_cast<unsigned long long>(key1 + 1);
  };
  std::vector<Face> faces;
  Index nonManifold = 0;
  for (Index p = begin; p < end; ++p)
  {
    // Room for every face through p; written in place (a face built aside
    // and copied in stalls on its partly written bytes).
    const size_t room = static_cast<size_t>(start[p + 1] - start[p]) * (Corners - 1);
    if (faces.size() < room)
    {
      faces.resize(room);
    }
    size_t count = 0;
    for (Id i = start[p]; i < start[p + 1]; ++i)
    {
      const Index c = static_cast<Index>(around[i]);
      const CellCorners ids = mesh.Cell(c);
      // Without branches (tested per corner, they were mispredicted).
      int at = -1;
      int times = 0;
      for (int l = 0; l < Corners; ++l)
      {
        const bool here = ids[l] == p;
        at = here ? l : at;
        times += here;
      }
      if (times != 1)
      {
        return -1;
      }
      // The faces through p: opposite each other corner.
      for (int k = 0; k < Corners; ++k)
      {
        if (k == at)
        {
          continue;
        }
        Index key0 = -1;
        Index key1 = -1;
        FaceOtherCorners<Corners>(ids, k, at, key0, key1);
        // Written in any case, kept (count advanced) unless matched at a
        // lower point: no branch. (Room for all faces through p.)
        Face& f = faces[count];
        f.Key = pack(key0, key1);
        f.Cell = c;
        f.Side = k;
        count += !(key0 >= 0 && key0 < p);
      }
    }
    // Triangles' faces through p, up to 8 of them (about 6 around a point
    // inside a 2D mesh): their keys (the other corner, in the high 32 bits)
    // with their places below, ordered by a fixed network of branch-free
    // exchanges (an insertion sort of the faces mispredicted a branch or
    // two per face), then the groups of equal keys as below.
    if constexpr (Corners == 3)
    {
      if (count <= 8)
      {
        unsigned long long order[8];
        for (size_t i = 0; i < 8; ++i)
        {
          order[i] = i < count ? faces[i].Key | i : ~0ULL;
        }
        SortEight(order);
        for (size_t a = 0; a < count;)
        {
          const unsigned long long key = order[a] >> 32;
          size_t b = a + 1;
          while (b < count && (order[b] >> 32) == key)
          {
            ++b;
          }
          if (b - a == 2)
          {
            PairFaces<Corners>(
              faces[order[a] & 0xffffffffULL], faces[order[a + 1] & 0xffffffffULL], neighbors);
          }
          else if (b - a > 2)
          {
            nonManifold += static_cast<Index>(b - a);
          }
          a = b;
        }
        continue;
      }
    }
    // Equal faces side by side, then each group: two cells are neighbours,
    // more share a non-manifold face.
    std::sort(faces.begin(), faces.begin() + count);
    for (size_t a = 0; a < count;)
    {
      size_t b = a + 1;
      while (b < count && faces[b].Same(faces[a]))
      {
        ++b;
      }
      if (b - a == 2)
      {
        PairFaces<Corners>(faces[a], faces[a + 1], neighbors);
      }
      else if (b - a > 2)
      {
        nonManifold += static_cast<Index>(b - a);
      }
      a = b;
    }
  }
  return nonManifold;
}

/**
 * The cells around each point (BuildPointCells' lists, 32-bit), as the
 * neighbours' construction built them: kept when asked, for the target
 * mass matrix's pattern (Transfer/MassMatrix.h), which needs the same lists.
 */
struct PointCells
{
  UninitializedLargeVector<std::int32_t> Start;
  UninitializedLargeVector<std::int32_t> Cells;
  /// Whether these are the lists of `mesh` (as many starts as its points, plus one).
  bool Fit(const MeshView& mesh) const
  {
    return !this->Start.empty() && static_cast<Index>(this->Start.size()) == mesh.AllPoints() + 1;
  }
};

/**
 * Fills `neighbors` with (CellDimension + 1) * NumberOfCells entries: for cell c
 * and face k (opposite corner k) the cell across, or -1, from the kernel's
 * own point-to-cell lists (BuildPointCells, in `runner`'s tasks) and
 * MatchFacesAtPoints over ranges of points in `runner`'s tasks (MatchFaces
 * when a cell names a point twice). Returns the number of non-manifold faces
 * found. The mesh must have fewer than 2^31 cells. With `keep`, the lists
 * are moved into it when they have 32-bit ids (else it is left empty).
 */
Index BuildFaceNeighbors(const MeshView& mesh, NeighborId* neighbors, const TaskRunner& runner,
  PointCells* keep = nullptr);
/// The same into a vector, on one task.
Index BuildFaceNeighbors(const MeshView& mesh, std::vector<NeighborId>& neighbors);

/**
 * The cells around every point, in CSR form: point p is used by the cells
 * cells[start[p]], ..., cells[start[p + 1] - 1] (in increasing order). The
 * vectors' element type (Index, or 32-bit to halve the memory) must hold
 * corners x cells. A counting sort: each task counts and places the uses
 * of its range of cells (per-task counts: at most as many tasks as uses
 * per point, so that they take no more memory than `cells`), the same
 * lists on any number of tasks.
 */
template <class Vector>
void BuildPointCells(const MeshView& mesh, Vector& start, Vector& cells, const TaskRunner& runner)
{
  using Id = typename Vector::value_type;
  const int corners = mesh.CornersPerCell();
  const Index np = mesh.AllPoints();
  const Index n = mesh.NumberOfCells;
  const Index uses = n * corners;
  const int tasks = static_cast<int>(
    std::min<Index>(runner.TasksFor(n, 16384), std::max<Index>(1, np > 0 ? uses / np : 1)));
  start.assign(static_cast<std::size_t>(np) + 1, 0);
  // Per task: its uses of each point, then where they go in the point's list.
  std::vector<Vector> count(static_cast<std::size_t>(tasks));
  runner.RunAll(tasks, [&](int k) {
    Vector& mine = count[k];
    mine.assign(static_cast<std::size_t>(np), 0);
    for (Index c = RangeBegin(n, k, tasks); c < RangeBegin(n, k + 1, tasks); ++c)
    {
      for (int j = 0; j < corners; ++j)
      {
        ++mine[mesh.Cell(c)[j]];
      }
    }
  });
  runner.ForRanges(np, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p)
    {
      Id before = 0;
      for (int k = 0; k < tasks; ++k)
      {
        const Id here = count[k][p];
        count[k][p] = before;
        before += here;
      }
      start[p + 1] = before;
    }
    return 0;
  });
  for (Index p = 0; p < np; ++p)
  {
    start[p + 1] += start[p];
  }
  cells.resize(static_cast<std::size_t>(start.back()));
  runner.RunAll(tasks, [&](int k) {
    Vector& mine = count[k];
    for (Index c = RangeBegin(n, k, tasks); c < RangeBegin(n, k + 1, tasks); ++c)
    {
      for (int j = 0; j < corners; ++j)
      {
        const Index p = mesh.Cell(c)[j];
        cells[start[p] + mine[p]++] = static_cast<Id>(c);
      }
    }
  });
}

/// The same on one task.
template <class Vector>
void BuildPointCells(const MeshView& mesh, Vector& start, Vector& cells)
{
  BuildPointCells(mesh, start, cells, TaskRunner());
}

/// The cells with at least one face without neighbour (mesh.Neighbors must
/// be set), in increasing order: the cells the front's walks can stop at.
void BoundaryCells(const MeshView& mesh, std::vector<Index>& cells);

/**
 * For a mesh of triangles (mesh.Neighbors set): how many edges its two
 * triangles run through in the same direction, i.e. the triangles on either
 * side are oriented against each other (0 for a consistently oriented
 * surface; a Moebius strip cannot have 0).
 */
Index MisorientedEdges(const MeshView& mesh);
} // namespace mp

#endif
