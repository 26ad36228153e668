// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file OperatorCache.h
 * @brief The operators the filter keeps between executions (time series on
 *        fixed meshes), per leaf of Input, keyed by the content of both
 *        meshes and the settings they depend on.
 *
 * A leaf's operators (M_tt and M_ts of each transfer in use, and of each
 * NaN group) are reused while its fingerprint is unchanged: same points,
 * cells, cell types and ghost cells of both meshes (compared by content:
 * readers build new arrays at every step), same search method, pieces
 * kept or not, and for surfaces the same contact settings. Each kept
 * operator also keeps its last solution, the next solve's start when the
 * same arrays come again.
 */
#ifndef MeshProjection_Projection_OperatorCache_h
#define MeshProjection_Projection_OperatorCache_h

#include "Projection/Transfers.h"

#include "Mesh/LargeArray.h"
#include "Transfer/Extrapolation.h"
#include "Transfer/LinearReconstruction.h"
#include "Transfer/MortarOperator.h"

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace mpvtk
{
class SimplexMesh;
struct Settings;

/// An operator kept between executions, with its last solution.
struct KeptOperator
{
  std::unique_ptr<mp::MortarOperator> Operator;
  std::string SolutionKey;          ///< GatheredFields::Key of the solution
  mp::LargeVector<double> Solution; ///< the last projection (warm start)
  /// The system of its last Apply (GetMatrix EXTRAPOLATION without an extension: the identity on its valid functions).
  mp::ProjectedSystem System;
  /// Extrapolation's extension over the operator's invalid functions (Projection/Extrapolation.h).
  mp::Extension Extension;
  const mp::MortarOperator* ExtensionFor = nullptr; ///< the operator it was built for
};

/// What the filter keeps for one leaf of Input.
struct KeptLeaf
{
  bool HasFingerprint = false;
  std::uint64_t GeometryFingerprint = 0;
  KeptOperator Operators[NumberOfTransfers];
  /// Kernel point -> dataset point of the kept operators' target and
  /// source, when renumbered (GetMatrix numbers rows and columns as the
  /// datasets' points).
  std::vector<mp::Index> TargetPoints, SourcePoints;
  /// NaN groups' operators, by transfer and fingerprint of the cells left out.
  std::map<std::pair<int, std::uint64_t>, std::unique_ptr<mp::MortarOperator>> Groups;

  void Clear();
  bool KeepsAny() const;
};

/// The geometry of the Source's cell reconstruction (CellReconstruction.h), while Source is the same.
struct KeptReconstruction
{
  std::uint64_t SourcePrint = 0; ///< SourceSide::Print of the mesh it was prepared on
  std::unique_ptr<mp::LinearReconstruction> Geometry;
};

class OperatorCache
{
public:
  /// By flat index of Input's leaf (0 for a dataset).
  std::map<unsigned int, KeptLeaf> Leaves;
  KeptReconstruction Reconstruction;

  /// The first leaf that keeps an operator of `transfer` (GetMatrix reads it), or null.
  const KeptLeaf* FirstLeaf(Transfer transfer) const;
  const mp::MortarOperator* FirstOperator(Transfer transfer) const;
  /// Bytes held by the kept operators and solutions (and the reconstruction's geometry).
  size_t MemoryBytes() const;
  /// Drops the leaves whose flat index is not in `present` (all, and the reconstruction, when `keep` is false).
  void KeepOnly(const std::vector<unsigned int>& present, bool keep);
};

/// The fingerprint that keys a leaf's operators.
std::uint64_t LeafFingerprint(
  const SimplexMesh& target, std::uint64_t sourcePrint, const Settings& settings, bool trace);
} // namespace mpvtk

#endif
