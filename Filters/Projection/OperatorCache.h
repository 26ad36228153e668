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
 * same arrays come again, and Extrapolation's extension, which serves again
 * for the same valid functions (keyed by their content).
 *
 * The policy lives here alone: a leaf looks its cache up at its start
 * (KeptLeaf::LookUp, Begin: a CachePlan the stages read) and stores what is
 * kept at its end (KeptLeaf::Store); in between the stages only ask.
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

struct LeafSolutions;
struct OperatorPlan;
struct OperatorSet;

/**
 * What the cache decides for one leaf, once, at its start
 * (KeptLeaf::LookUp): the stages read this value, never the setting
 * (CacheOperator), for what is kept and what may serve again.
 */
struct CachePlan
{
  std::uint64_t Fingerprint = 0; ///< the leaf's (LeafFingerprint)
  bool Keep = false; ///< operators built with M_ts are kept at the leaf's end (KeptLeaf::Store)
  bool SameGeometry =
    false;            ///< the kept operators may serve (the caller agrees it over the processes)
  bool Asked = false; ///< M_ts asked for: the inputs vary in time, or KeepMatrices
  /// M_ts formed so that the operators can be kept: time steps, meshes that came again, KeepMatrices.
  bool Assembles() const { return this->Keep && (this->Asked || this->SameGeometry); }
  /// Whether `op` (built here) will be kept at the leaf's end.
  bool Keeps(const mp::MortarOperator& op) const { return this->Keep && op.HasMixedMass(); }
};

/// An operator kept between executions, with its last solution.
struct KeptOperator
{
  std::unique_ptr<mp::MortarOperator> Operator;
  std::string SolutionKey;          ///< GatheredFields::Key of the solution
  mp::LargeVector<double> Solution; ///< the last projection (warm start)
  /// The system of its last Apply (GetMatrix EXTRAPOLATION without an extension: the identity on its valid functions).
  mp::ProjectedSystem System;
  /// Extrapolation's extension of the last execution over the operator's invalid functions (Projection/Extrapolation.h).
  mp::Extension Extension;
  std::uint64_t ExtensionKey = 0; ///< ExtensionKey of it (0: none)
};

/**
 * The key of an extension (Extrapolation): the mode and the content of the
 * valid functions it extends from. On one leaf's target (its fingerprint
 * unchanged) an extension with the same key is the same extension.
 */
std::uint64_t ExtensionKey(mp::ExtrapolationMode mode, const std::vector<char>& valid);

/// A NaN group's operator: its transfer and the fingerprint of the Source cells it leaves out.
using GroupKey = std::pair<int, std::uint64_t>;

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
  std::map<GroupKey, std::unique_ptr<mp::MortarOperator>> Groups;

  void Clear();
  bool KeepsAny() const;

  // The policy, in the order a leaf asks (LeafProjection.h).
  /**
   * At the leaf's start: what is kept this time, and whether the kept
   * operators may serve (the same LeafFingerprint); `timeVarying`: the
   * inputs are a time series.
   */
  CachePlan LookUp(const SimplexMesh& target, std::uint64_t sourcePrint, const Settings& settings,
    bool trace, bool timeVarying) const;
  /// Once `plan` is agreed: the kept operators dropped unless they may serve; the fingerprint noted.
  void Begin(const CachePlan& plan);
  /// The kept operator of `transfer` (null: none).
  const mp::MortarOperator* Operator(Transfer transfer) const
  {
    return this->Operators[transfer].Operator.get();
  }
  /// The kept operator of a NaN group (null: none).
  const mp::MortarOperator* Group(Transfer transfer, std::uint64_t cellsLeftOut) const;
  /// Drops the kept NaN groups' operators that this leaf does not use.
  void KeepOnlyGroups(const std::vector<GroupKey>& used);
  /// The kept solution of `transfer`'s operator for the fields `key` (`size` values), the next solve's start; null: none.
  const mp::LargeVector<double>* WarmStart(
    Transfer transfer, const std::string& key, size_t size) const;
  /// The kept extension of `transfer` with the key `key` (ExtensionKey); null: none.
  const mp::Extension* Extension(Transfer transfer, std::uint64_t key) const;
  /**
   * At the leaf's end: keeps what plan.Cache says (the operators built with
   * M_ts, with their solutions, systems and extensions, the NaN groups'
   * operators, the meshes' point orders) and drops the rest (and the
   * operators of transfers not in use); the operators built here and not
   * kept give back their matrices.
   */
  void Store(const OperatorPlan& plan, OperatorSet& ops, LeafSolutions& solutions,
    const SimplexMesh& target, const SimplexMesh& source);
};

/// The geometry of the Source's cell reconstruction (CellReconstruction.h), while Source is the same.
struct KeptReconstruction
{
  std::uint64_t SourcePrint = 0; ///< SourceSide::Print of the mesh it was prepared on
  std::unique_ptr<mp::LinearReconstruction> Geometry;
  /// After the reconstruction: kept for the next execution with CacheOperator, else given back.
  void Store(const Settings& settings);
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
  /// Drops the leaves whose flat index is not in `present` (all, and the reconstruction, when the settings keep nothing).
  void KeepOnly(const std::vector<unsigned int>& present, const Settings& settings);
};

/// The fingerprint that keys a leaf's operators.
std::uint64_t LeafFingerprint(
  const SimplexMesh& target, std::uint64_t sourcePrint, const Settings& settings, bool trace);
} // namespace mpvtk

#endif
