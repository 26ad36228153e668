// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file LeafProjection.h
 * @brief One leaf of Input projected: the stages in order.
 *
 * 1. The target as the kernel's mesh (on several processes first sharing
 *    its points with the other processes: a SharedTarget, Parts.h).
 * 2. Its shape with the Source (Shape.h): dimension, trace, frames.
 * 3. The operators: the cache looked up (OperatorCache.h: a CachePlan),
 *    kept ones or built (OperatorBuild.h).
 * 4. What the solves do not need goes (the search structures; for the last
 *    leaf the meshes' geometry, once what the outputs take from it is
 *    taken), and M_tt is completed.
 * 5. The solves (Apply.h) and the extrapolation (Extrapolation.h), then
 *    what the cache keeps stored (KeptLeaf::Store).
 * 6. The outputs (Outputs.h).
 * On several processes the processes agree at three named rounds
 * (Agreement.h), so that all go on or end together.
 */
#ifndef MeshProjection_Projection_LeafProjection_h
#define MeshProjection_Projection_LeafProjection_h

#include "Projection/Leaf.h"

#include <string>

class vtkDataSet;

namespace mpvtk
{
struct KeptLeaf;

/// What the execution hands one leaf.
struct LeafJob
{
  vtkDataSet* Target;      ///< Input's dataset
  vtkDataSet* Output;      ///< its copy in output 0, which receives the arrays
  std::string Role;        ///< "Input" or "Input block ..." in messages
  ProgressShare Bar;       ///< this leaf's share of the progress bar
  bool LastReaderOfSource; ///< no later leaf reads the Source mesh
};

/// What the leaf's stages share with the execution.
struct ExecutionShare
{
  const Settings& Options;
  Parts& Processes;
  Messages& Say;
  StageClock& Clock;
  SourceSide& Source;
};

/// Projects one leaf; the statistics are the leaf's own, for the caller to add up.
LeafResult ProjectLeaf(const ExecutionShare& run, const LeafJob& job, KeptLeaf& kept);
} // namespace mpvtk

#endif
