// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Extrapolation.h
 * @brief Values beyond the source: the valid values of a projection
 *        extended over the target's graph into the functions the source
 *        does not reach.
 *
 * Two extensions, both linear in the valid values:
 *
 * - Smooth: the harmonic extension over the graph, L_uu x_u = -L_ub x_b,
 *   with L the graph Laplacian whose edge weights are the number of cells
 *   holding both ends (a sum over cells, so that the parts of a distributed
 *   target add up to the whole one). Each extended value is a weighted
 *   mean of its neighbours': within the valid values' range, no new
 *   extrema (discrete maximum principle), "creep fill".
 * - Nearest: the value of the nearest valid function along the graph
 *   (edge lengths between the functions' positions).
 *
 * Functions in parts of the graph connected to no valid function keep
 * their (fill) value.
 */
#ifndef MeshProjection_Kernel_Extrapolation_h
#define MeshProjection_Kernel_Extrapolation_h

#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"
#include "Transfer/BlockCG.h"

#include <vector>

namespace mp
{
/// A weighted graph over a space's functions (compressed rows, no self loops).
struct FunctionGraph
{
  std::vector<Index> Start{ 0 };
  std::vector<Index> Neighbors;
  std::vector<double> Weights;   ///< cells holding both ends
  std::vector<double> Positions; ///< 3 per function (points, or cell centroids)
  Index Size() const { return static_cast<Index>(this->Start.size()) - 1; }
};

/// P1 functions: points joined by the edges of the simplices.
FunctionGraph PointGraph(const MeshView& mesh);
/// P0 functions: original cells (parents) joined when their simplices share a point.
FunctionGraph CellGraph(const MeshView& mesh);

enum class ExtrapolationMode
{
  None = 0,
  Smooth = 1,
  Nearest = 2
};

/**
 * Extends columns [offset, offset + nc) of `values` (functions x width)
 * from the functions with valid[f] to the others that the graph connects
 * to one. `extrapolated` (resized) says which got a value. `hooks`: a
 * distributed graph (Exchange sums shared rows, Reduce sums counts); the
 * smooth extension is then the whole graph's, the nearest the nearest
 * within each part. Returns the functions left without a value (counted
 * once: hooks.Counted). False in `ok` when the smooth system could not be
 * solved.
 */
Index Extrapolate(const FunctionGraph& graph, const std::vector<char>& valid, double* values,
  int width, int offset, int nc, ExtrapolationMode mode, const TaskRunner& runner,
  const SolverHooks& hooks, std::vector<char>& extrapolated, bool& ok);
} // namespace mp

#endif
