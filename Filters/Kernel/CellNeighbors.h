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

#include <vector>

namespace mp
{
/**
 * Fills `neighbors` with (Dimension + 1) * NumberOfCells entries: for cell c
 * and face k (opposite corner k) the cell across, or -1. Returns the number
 * of non-manifold faces found.
 */
Index BuildFaceNeighbors(const MeshView& mesh, std::vector<Index>& neighbors);

/// The cells around every point, in CSR form: point p is used by the cells
/// cells[start[p]], ..., cells[start[p + 1] - 1] (in increasing order).
void BuildPointCells(const MeshView& mesh, std::vector<Index>& start, std::vector<Index>& cells);

/// The cells with at least one face without neighbour (mesh.Neighbors must
/// be set), in increasing order: the cells the front's walks can stop at.
void BoundaryCells(const MeshView& mesh, std::vector<Index>& cells);
} // namespace mp

#endif
