// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CellNeighbors.h
 * @brief Face neighbours of a simplicial mesh, without VTK.
 *
 * One face matcher (MatchFaces) for every caller: for each face, the cells
 * around its first corner that hold its other corners. Where the cells
 * around a point come from is the caller's: BuildFaceNeighbors takes them
 * from the kernel's own point-to-cell lists (a counting sort; for the tests,
 * the benchmark and any caller without VTK), the VTK filter from VTK's
 * static cell links. Linear time. A face shared by more than two cells (a
 * non-manifold mesh) gets no neighbour, and their number is returned.
 */
#ifndef MeshProjection_Kernel_CellNeighbors_h
#define MeshProjection_Kernel_CellNeighbors_h

#include "Mesh/MeshView.h"

#include <cstddef>
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
    const Index* ids = mesh.Cell(c);
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
        const Index* o = mesh.Cell(other);
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
          const Index* o = mesh.Cell(found);
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
 * Fills `neighbors` with (CellDimension + 1) * NumberOfCells entries: for cell c
 * and face k (opposite corner k) the cell across, or -1. Returns the number
 * of non-manifold faces found. The mesh must have fewer than 2^31 cells.
 */
Index BuildFaceNeighbors(const MeshView& mesh, std::vector<NeighborId>& neighbors);

/// The cells around every point, in CSR form: point p is used by the cells
/// cells[start[p]], ..., cells[start[p + 1] - 1] (in increasing order). The
/// vectors' element type (Index, or 32-bit to halve the memory) must hold
/// corners x cells.
template <class Vector>
void BuildPointCells(const MeshView& mesh, Vector& start, Vector& cells)
{
  using Id = typename Vector::value_type;
  const int corners = mesh.CornersPerCell();
  start.assign(static_cast<std::size_t>(mesh.NumberOfPoints) + 1, 0);
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    for (int k = 0; k < corners; ++k)
    {
      ++start[mesh.Cell(c)[k] + 1];
    }
  }
  for (Index p = 0; p < mesh.NumberOfPoints; ++p)
  {
    start[p + 1] += start[p];
  }
  cells.resize(static_cast<std::size_t>(start.back()));
  Vector fill(start.begin(), start.end() - 1);
  for (Index c = 0; c < mesh.NumberOfCells; ++c) // cell ids come out sorted per point
  {
    for (int k = 0; k < corners; ++k)
    {
      cells[fill[mesh.Cell(c)[k]]++] = static_cast<Id>(c);
    }
  }
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
