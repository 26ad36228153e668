// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Conservation.h
 * @brief The integrals the filter reports for each projected array, and
 *        the optional scaling to the Source's own integral.
 *
 * SourceIntegral_<array> is the Source field's integral over the part of
 * Source the operator's pieces cover: per Source function a weight (P1: a
 * third (a half, a quarter) of the covered measure of each simplex around
 * the point; P0: the cell's covered measure; DP1, reconstructed cell data,
 * and the second-order cells' own functions: each one's integral over the
 * covered part), NaN groups' cells not covered.
 * For surfaces and curves the pieces, projected along each target
 * facet's own normal, cover a Source cell only up to O(h^2): a cell
 * covered to 90% or more counts whole, so that a Source covered whole gives
 * its own integral exactly. On several processes each process has its part
 * of a cell's cover; for that rule, which is not linear, the parts are
 * summed over the processes (by the cells' corners' global ids) first.
 * TargetIntegral_<array> is the projection's integral over the covered
 * target (equal to the projected Source field's). Sums are taken in
 * blocks, in block order: the same on any number of threads.
 */
#ifndef MeshProjection_Projection_Conservation_h
#define MeshProjection_Projection_Conservation_h

#include "vtkType.h"

#include "Mesh/LargeArray.h"
#include "Transfer/MortarOperator.h"

#include <map>
#include <string>
#include <utility>
#include <vector>

class vtkDataSet;

namespace mpvtk
{
class Messages;
class Parts;
class SimplexMesh;

/// The Source functions' covered measures (the weights of SourceIntegral_), per operator.
class SourceWeights
{
public:
  SourceWeights(const SimplexMesh& source, vtkDataSet* sourceData, Parts& parts)
    : Source(source)
    , SourceData(sourceData)
    , Processes(parts)
  {}
  /**
   * The weights of `op`'s Source functions (its source space's: points,
   * cells, or the corners of each simplex). Collective on several
   * processes (every process calls it for the same arrays, in the same order).
   */
  const std::vector<double>& Of(const mp::MortarOperator& op);
  /// As Of(), on this process alone: for one process, before the Source mesh goes.
  void Weigh(const mp::MortarOperator& op);

private:
  std::vector<double> CoveredTotals(const mp::MortarOperator& op, bool needed);
  const std::vector<double>& Make(const mp::MortarOperator& op, const std::vector<double>& total);
  const SimplexMesh& Source;
  vtkDataSet* SourceData;
  Parts& Processes;
  std::map<const mp::MortarOperator*, std::vector<double>> Weights;
};

/// One array's integrals over Source and target (per component), and the scale of each component.
struct ArrayIntegrals
{
  std::vector<double> Source;
  std::vector<double> Target;
  std::vector<double> Factor; ///< ConserveSourceIntegral's scale (1: unscaled)
};

/// What Integrate reads of one projected array.
struct ProjectedArray
{
  const mp::ProjectedSystem&
    System; ///< the system the result was solved in (its valid functions, covered integrals)
  const std::vector<double>& Weights; ///< SourceWeights::Of
  /// The Source functions' values, `SourceWidth` per row, the array's from
  /// column `SourceOffset`: its NaN group's when it has one (non-finite values as
  /// 0 there, on cells the operator leaves out), since the gathered block holds 0.
  const mp::LargeVector<double>& Source;
  int SourceWidth;
  int SourceOffset;
  const mp::LargeVector<double>& Result; ///< the target functions' values, `Width` per row
  int Width;
  int Offset; ///< the array's first column in Result
  int Components;
  vtkIdType TargetFunctions;
};

/**
 * The integrals of one array, summed over the processes; with
 * `conserveSource` (not for traces), each component whose two integrals are
 * within a factor 2 is scaled to the Source's (else said once, by `name`).
 */
ArrayIntegrals Integrate(const ProjectedArray& array, bool conserveSource, const std::string& name,
  const std::string& role, Parts& parts, Messages& messages);
} // namespace mpvtk

#endif
