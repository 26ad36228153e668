// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CellNeighbors.h
 * @brief Face neighbours of a simplicial mesh, without VTK.
 *
 * The VTK filter builds neighbours with VTK's cell links; this builder serves
 * the kernel's own tests, the benchmark and any caller without VTK. It does
 * the same: point-to-cell links (a counting sort), then for each face the
 * cells around its first corner. Linear time. A face shared by more than two
 * cells (a non-manifold mesh) gets no neighbour, and their number is returned.
 */
#ifndef MeshProjection_Kernel_CellNeighbors_h
#define MeshProjection_Kernel_CellNeighbors_h

#include "MeshView.h"

#include <cstddef>
#include <vector>

namespace mp
{
/**
 * Fills `neighbors` with (Dimension + 1) * NumberOfCells entries: for cell c
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
} // namespace mp

#endif
