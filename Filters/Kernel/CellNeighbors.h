// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CellNeighbors.h
 * @brief Face neighbours of a simplicial mesh, without VTK.
 *
 * The VTK filter builds neighbours with VTK's cell links; this builder serves
 * the kernel's own tests, the benchmark and any caller without VTK. It sorts
 * the faces (O(n log n)); a face shared by more than two cells (a
 * non-manifold mesh) gets no neighbour, and that count is returned.
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
} // namespace mp

#endif
