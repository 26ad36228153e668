// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Leaf.h
 * @brief The values one leaf's stages pass along: what they all read
 *        (LeafContext), which operators to use (OperatorPlan), the operators
 *        themselves (OperatorSet) and what the leaf returns (LeafResult).
 *
 * A leaf is one dataset of Input: its own mesh, its own system
 * M_tt u_t = M_ts u_s per transfer. The stages, in order (LeafProjection.h):
 * wrap the target, decide the shape (Shape.h), plan and build the
 * operators (OperatorBuild.h), weigh the Source for the conservation
 * figures (Conservation.h), apply the operators (Apply.h), write the
 * outputs (Outputs.h).
 */
#ifndef MeshProjection_Projection_Leaf_h
#define MeshProjection_Projection_Leaf_h

#include "Parallel/Parts.h"
#include "Projection/OperatorCache.h"
#include "Projection/Progress.h"
#include "Projection/Shape.h"
#include "Projection/Statistics.h"
#include "Projection/Transfers.h"

#include "Transfer/MortarOperator.h"

#include "vtkSmartPointer.h"

#include <memory>
#include <string>
#include <vector>

class vtkDataObject;
class vtkDataSet;

namespace mpvtk
{
class Messages;
class SimplexMesh;
struct Settings;
struct SourceSide;

/// What every stage of one leaf reads (and the leaf's clock and statistics, which they add to).
struct LeafContext
{
  const Settings& Options;
  Parts& Processes;
  Messages& Say;
  ProgressShare Bar;
  StageClock& Clock;
  Statistics& Stats;
  SourceSide& Source;
  SimplexMesh& Target;
  vtkDataSet* TargetData; ///< Input's dataset (with global point ids on several processes)
  const SharedTarget&
    Shared; ///< it as the processes share it (Parts::ShareTarget): the hooks and the halo are made from it
  std::string Role; ///< "Input" or "Input block ..." in messages
  LeafShape Shape;
  bool LastReaderOfSource; ///< no later leaf reads the Source mesh
};

/// Which operators one leaf uses, and how they are made.
struct OperatorPlan
{
  bool Used[NumberOfTransfers] = {};
  /// What the operator cache keeps and lets serve (Cache.SameGeometry: on every process).
  CachePlan Cache;
  /// M_ts formed (bounds need it; kept operators with time steps, meshes
  /// that came again, or KeepMatrices); else the fields' right-hand sides are
  /// summed during the search and M_ts is never formed.
  bool Assembled = false;
};

/// The operators of one leaf: kept ones and those built by this execution.
struct OperatorSet
{
  std::unique_ptr<mp::MortarOperator> Fresh[NumberOfTransfers];
  const mp::MortarOperator* Operators[NumberOfTransfers] = {};
  /// Per transfer, the operator of each Source array (its NaN group's, or the transfer's).
  std::vector<const mp::MortarOperator*> ByArray[NumberOfTransfers];
  /// NaN groups' operators built here, by transfer and fingerprint of the cells left out (KeptLeaf::Groups).
  std::vector<std::pair<GroupKey, std::unique_ptr<mp::MortarOperator>>> GroupFresh;
  /// The operators built here, whose M_tt comes once the Source is released.
  std::vector<mp::MortarOperator*> Deferred;

  /// The first operator in use: coverage, statistics, pieces.
  const mp::MortarOperator* First() const;
  bool BuiltAny() const;
};

/// What one leaf returns to the execution.
struct LeafResult
{
  Verdict Outcome;
  Statistics Stats;
  vtkSmartPointer<vtkDataObject> Pieces; ///< the intersection pieces, when asked for
};
} // namespace mpvtk

#endif
