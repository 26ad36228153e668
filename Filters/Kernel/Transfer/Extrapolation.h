// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Extrapolation.h
 * @brief Values beyond the source: the valid values of a projection
 *        extended over the target's graph into the functions the source
 *        does not reach.
 *
 * Two extensions, both linear in the valid values:
 *
 * - Smooth ("creep fill"): layer by layer away from the valid functions,
 *   each function takes the weighted mean of its neighbours in the layers
 *   before it; then sweeps of neighbour means (Jacobi, towards the
 *   harmonic extension) smooth the layers' traces. The edge weights are
 *   the number of cells holding both ends (a sum over cells, so that the
 *   parts of a distributed target add up to the whole one). Every value is
 *   a weighted mean of valid ones: within their range, no new extrema.
 * - Nearest: the value of the nearest valid function along the graph
 *   (edge lengths between the functions' positions).
 *
 * Functions in parts of the graph connected to no valid function keep
 * their (fill) value. The graph holds rows for the functions to extend
 * only, so the cost follows the part beyond the source.
 */
#ifndef MeshProjection_Kernel_Extrapolation_h
#define MeshProjection_Kernel_Extrapolation_h

#include "Mesh/MeshView.h"
#include "Transfer/BlockCG.h"

#include <vector>

namespace mp
{
/// A weighted graph over a space's functions, with rows for some of them.
struct FunctionGraph
{
  std::vector<Index> Row;        ///< per function: its row, or -1
  std::vector<Index> Start{ 0 }; ///< per row
  std::vector<Index> Neighbors;
  std::vector<double> Weights;   ///< cells holding both ends
  std::vector<double> Positions; ///< 3 per function (points, or cell centroids)
  Index Size() const { return static_cast<Index>(this->Row.size()); }
};

/// P1 functions: points joined by the edges of the simplices; rows for `want`.
FunctionGraph PointGraph(const MeshView& mesh, const std::vector<char>& want);
/// P0 functions: original cells (parents) joined when their simplices share a point; rows for `want`.
FunctionGraph CellGraph(const MeshView& mesh, const std::vector<char>& want);

enum class ExtrapolationMode
{
  None = 0,
  Smooth = 1,
  Nearest = 2
};

/**
 * Extends columns [offset, offset + nc) of `values` (functions x width)
 * from the functions with valid[f] to the others that the graph connects
 * to one (the graph must have rows for the functions not valid).
 * `extrapolated` (resized) says which got a value. `hooks`: a distributed
 * graph (Exchange sums shared rows, ExchangeMinimum completes layers,
 * Reduce sums counts); the smooth extension is then the whole graph's, the
 * nearest the nearest within each part. Returns the functions left without
 * a value (counted once: hooks.Counted).
 */
Index Extrapolate(const FunctionGraph& graph, const std::vector<char>& valid, double* values,
  int width, int offset, int nc, ExtrapolationMode mode, const SolverHooks& hooks,
  std::vector<char>& extrapolated);
} // namespace mp

#endif
