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
 *   before it. The edge weights are the number of cells holding both ends
 *   (a sum over cells, so that the parts of a distributed target add up to
 *   the whole one). Every value is a weighted mean of valid ones: within
 *   their range, no new extrema. (No smoothing sweeps after the layers:
 *   a layer reads only earlier ones, so the extension is one pass, the
 *   same on one process as on several, and exported as one matrix.)
 * - Nearest: the value of the nearest valid function along the graph
 *   (edge lengths between the functions' positions).
 *
 * Functions in parts of the graph connected to no valid function keep
 * their (fill) value. The graph holds rows for the functions to extend
 * only, so the cost follows the part beyond the source; a function that
 * is neither valid nor has a row is left alone (not read, not extended).
 */
#ifndef MeshProjection_Kernel_Extrapolation_h
#define MeshProjection_Kernel_Extrapolation_h

#include "Mesh/MeshView.h"
#include "Transfer/BlockCG.h"
#include "Transfer/CsrMatrix.h"

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
 * A linear extension of the valid functions' values to the others that the
 * graph connects to one: steps in order, each function of a step the
 * weighted mean of functions it reads, which are valid or in earlier steps
 * (so the extension is a product of sparse means: linear in the data, every
 * value within the valid values' range).
 */
struct Extension
{
  ExtrapolationMode Mode = ExtrapolationMode::None;
  std::vector<char> Valid;               ///< per function: valid, what the extension reads
  std::vector<char> Extended;            ///< per function: given a value
  std::vector<std::vector<Index>> Steps; ///< the functions of each step (as many on every part)
  CsrMatrix Reads; ///< per function, what its mean reads, with weights (this part's share)
  Index Unreached =
    0; ///< functions with rows connected to no valid one (counted once over the parts)
};

/**
 * The extension of `mode` from the functions with valid[f] to those the
 * graph has rows for (a function with neither is neither read nor
 * extended nor counted in Unreached: one whose value is known not to be
 * the field's, e.g. a mass-weighted array's where the density guard left
 * it undivided). Smooth: step L holds the functions L edges
 * from the valid ones, each reading its neighbours of earlier steps with
 * the graph's weights. Nearest: one step, each function reading the
 * nearest valid one along the graph. `hooks`: a distributed graph
 * (ExchangeMinimum completes the layers, Reduce counts): the steps are
 * then the whole graph's, the nearest the nearest within each part.
 */
Extension ExtendOver(const FunctionGraph& graph, const std::vector<char>& valid,
  ExtrapolationMode mode, const SolverHooks& hooks);

/**
 * Columns [offset, offset + nc) of `values` (functions x width): the
 * extended functions' values, step by step. On a distributed graph each
 * step's sums are completed across the parts (hooks.Exchange): a shared
 * function's mean is over all its neighbours, the same on every part.
 */
void ApplyExtension(const Extension& extension, double* values, int width, int offset, int nc,
  const SolverHooks& hooks);

/**
 * The extension as one matrix E (functions x functions) over the valid
 * functions: E u is the extended field of valid values u (valid rows the
 * identity, unreached rows empty). One process's graph.
 */
CsrMatrix ComposedExtension(const Extension& extension, const std::vector<char>& valid);
} // namespace mp

#endif
