// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MortarOperator.h
 * @brief The mortar L2 projection between two meshes: built once from their
 *        geometry, applied to any number of fields.
 *
 * For a target space (basis phi_i) and a source space (basis psi_j), see
 * Space.h, the projection u_t of a source field u_s solves
 *
 *     M_tt u_t = M_ts u_s,  (M_tt)_ik = int phi_i phi_k,  (M_ts)_ij = int phi_i psi_j,
 *
 * both integrals taken over T intersected with S, i.e. summed over the
 * intersection pieces of all (target, source) cell pairs that the pair
 * search finds. Integrating M_tt over the covered part (rather than over
 * all of T) keeps the two properties users rely on even when the meshes do
 * not cover the same domain: a source field in the target space is
 * reproduced exactly (linear fields by P1, constants by P0), and the
 * integral of u_t over the covered part equals that of u_s.
 *
 * Target functions whose support meets no source cell cannot be determined:
 * they are reported invalid and receive a fill value (their rows of M_tt
 * hold a 1 on the diagonal).
 *
 * Build() takes the two geometries alone: it runs the search, which sums
 * M_ts (compressed rows, target functions x source functions) and leaves
 * per target cell what M_tt takes from it, then assembles M_tt (compressed
 * rows over the target space's pattern) from the target alone
 * (MassMatrix.h; OperatorOptions::DeferTargetMass lets the caller free the
 * source first). Apply() then projects any
 * field, as often as wanted: M_ts u_s, then the block conjugate gradients
 * (BlockCG.h). Both matrices can be read out.
 *
 * For a single use, the fields can be named at Build() instead
 * (OperatorOptions::Fields): their right-hand sides M_ts u_s are summed
 * during the search and M_ts is not stored, which saves the time and the
 * memory of assembling it (a large part of a 2D run); Apply() then
 * projects those fields only.
 */
#ifndef MeshProjection_Kernel_MortarOperator_h
#define MeshProjection_Kernel_MortarOperator_h

#include "Geometry/IntersectionPieces.h"
#include "Mesh/MeshView.h"
#include "Mesh/NodalCells.h"
#include "Mesh/Tasks.h"
#include "Search/CandidateLocator.h"
#include "Search/SearchStatistics.h"
#include "Transfer/BernsteinForm.h"
#include "Transfer/BlockCG.h"
#include "Transfer/CsrMatrix.h"
#include "Transfer/FringeAggregation.h"
#include "Transfer/MassMatrix.h"
#include "Transfer/MixedMatrix.h"
#include "Transfer/Space.h"

#include <memory>
#include <string>
#include <vector>

namespace mp
{
struct OperatorOptions
{
  SearchMethod Method = SearchMethod::AdvancingFront;
  SpaceType TargetSpace = SpaceType::P1;
  SpaceType SourceSpace = SpaceType::P1;
  bool KeepPieces = false; ///< store the intersection pieces (GetPieces)
  /**
   * Single use: the source fields to project (source functions x
   * FieldComponents, row-major; they must outlive Build). Their right-hand
   * sides are summed during the search and M_ts is not stored: Apply()
   * then takes these fields only. Null (default): M_ts is assembled and
   * Apply() takes any field.
   */
  const double* Fields = nullptr;
  int FieldComponents = 0;
  /**
   * Per source cell (kernel numbering): nonzero to leave the cell out, as if
   * the source had a hole there (e.g. cells without data for a field: NaN
   * values). The search still walks through it, but its pieces add nothing:
   * the covered part, M_tt, M_ts, the valid functions and the covered
   * fractions are those of the other cells. Null (default): every cell counts.
   */
  const char* ExcludedSourceCells = nullptr;
  /// Concurrent tasks for the search, the assembly and the solve, and how
  /// they run (default: one, serial).
  TaskRunner Runner;
  /// Progress of the search, and a way to stop it (Tasks.h); Build() then
  /// returns false with GetError() "stopped".
  ProgressHook Progress;
  /**
   * Build() and BuildTogether() stop after the search: M_tt (and with it
   * the valid functions, the covered integrals and the solver) is
   * assembled by CompleteTargetMass(), which needs the target's geometry
   * only. A caller can give back the source's arrays and both meshes'
   * neighbours in between, so that they and M_tt are never alive at once.
   * Until then the operator holds, for M_tt, only what it takes from each
   * target cell (MassMatrix.h: a float per cell, and the blocks of the cells
   * covered in part), besides its right-hand sides or M_ts and the covered
   * fractions (per kernel cell until then).
   */
  bool DeferTargetMass = false;
};

/// How Apply() turns the right-hand sides into the projected field.
enum class MassType
{
  /**
   * M_tt as integrated: the L2 projection (exact for fields of the target
   * space, second order), which may overshoot the source's range near
   * discontinuities.
   */
  Consistent = 0,
  /**
   * M_tt lumped to its row sums d_i = int phi_i over the covered part:
   * u_i = (M_ts u_s)_i / d_i. M_ts's entries are non-negative and its row
   * sums are d_i too, so each value is a weighted mean of the source values
   * on its support (never outside their range), the integral is conserved,
   * and no system is solved; but only constants stay exact (first order).
   * On a target whose point functions are its second-order cells' own
   * (HasNodalTarget) the nodal functions' integrals are zero or negative
   * at corners, so no row sum is a weight of a mean: the field is lumped
   * in the same space's Bernstein basis (BernsteinForm.h), non-negative
   * functions B_m that sum to 1: b_m = int B_m u_s / int B_m over the
   * covered part, a mean of the source field on B_m's support, and the
   * node values u = C b. Constants stay exact, the integral is conserved,
   * and the whole field (not only its nodes) lies within the range of the
   * b_m. On Quad8, Hexa20, Wedge15 and Pyramid13 the form may be signed
   * (BernsteinForm.h: non-negative on affine Quad8, Hexa20, Wedge15, not
   * on pyramids nor always elsewhere): b_m = int Psi_m u_s / int Psi_m
   * keeps constants and the integral but need not be a mean, so the b_m
   * are then always clipped to their rows' bounds as ApplyOptions::Bounded
   * does (needs M_ts; a distributed Apply sets Bounded on every part when
   * any part has such cells): the nodes lie within the bounds, the field
   * between them where the Psi_m are non-negative.
   * Refused (Apply's Ok false) on a target with no form (BernsteinForm::Covers).
   */
  Lumped = 1
};

/**
 * A distributed target's ghost layer for the fringe (AggregateFringe): the
 * cells of the other parts near this part's points, so that each part
 * finds the stencils the whole target gives. Its points are rows n, n + 1,
 * ... after this part's n target functions (the extended rows); Hooks work
 * on the extended rows: a ghost row is shared with the parts that have its
 * point (as theirs or as a ghost), summed like a shared row, never counted.
 */
struct FringeHalo
{
  std::vector<double> Points; ///< 3 coordinates per ghost point
  /// The target's corners per cell, in the extended rows, or, for the
  /// geometric-only points of curved cells split finer (MeshView::
  /// GeometricPoints), n + NumberOfPoints() + k for Geometric's point k.
  std::vector<Index> Cells;
  /// 3 coordinates per geometric-only point of the halo's refined simplices
  /// (no function and no row: their parents' nodes are the functions).
  std::vector<double> Geometric;
  /// A second-order target's ghost parents, so that its fringe finds the
  /// root cells (FringeRoots.h) the whole target gives: per cell of Cells
  /// its parent among ParentTypes (all empty for a linear target).
  std::vector<Index> CellParents;
  std::vector<NodalType> ParentTypes;   ///< None: linear, or a node the halo lacks
  std::vector<long long> ParentOffsets; ///< ParentTypes.size() + 1 entries
  std::vector<long long> ParentNodes;   ///< each parent's nodes, in the extended rows
  SolverHooks Hooks;
  Index NumberOfPoints() const { return static_cast<Index>(this->Points.size() / 3); }
};

struct ApplyOptions
{
  MassType Mass = MassType::Consistent;
  /**
   * Bound preservation: after a consistent projection, clip every target
   * value to the range of the source values on its support (the columns of
   * its row of M_ts), then give back the clipped integral in proportion to
   * the room each value has left within its bounds (clip and assured sum,
   * Bradley, Bosler and Guba 2019). The integral stays that of the source
   * field over the covered part, values stay within their local bounds, and
   * a field that needs no clipping (e.g. a linear one) is unchanged. Needs
   * the assembled M_ts.
   * On a target in its second-order cells' own space the Bernstein
   * coefficients of the field (BernsteinForm.h) are clipped instead, each
   * to the bounds of its node's row, with the Bernstein functions'
   * integrals as the positive weights: the field lies within the bounds
   * everywhere in each cell (a convex combination of its coefficients),
   * its nodes included, and its integral is kept. With Lumped the
   * coefficients, means of the source field, are clipped alike (a
   * second-order source's field may pass its node values between them).
   * On Quad8, Hexa20, Wedge15 and Pyramid13 the nodes lie within the
   * bounds and the integral is kept, the field between the nodes where
   * the form's functions are non-negative (affine Quad8, Hexa20, Wedge15).
   * Refused where the target has no form.
   */
  bool Bounded = false;
  /// Some process's target has a signed form (BernsteinForm::HasSigned
  /// over all processes): its rows that weigh nothing where covered are set
  /// alike on every process, and Lumped is always clipped. On one process
  /// the operator's own form says it as well.
  bool Signed = false;
  SolveOptions Solve;
  /// A distributed system whose fringe was aggregated with a FringeHalo:
  /// that halo's Hooks, for the aggregated solve (its extended rows).
  const SolverHooks* FringeHooks = nullptr;
};

/**
 * The system whose solution an Apply() wrote, and what a result is read
 * with: its valid functions (the others got the fill value), their covered
 * integrals (sum_i over the valid functions of CoveredIntegrals_i u_i is
 * the integral of u over the covered part) and how many are valid. Either
 * M_tt's own (MortarOperator::GetAssembledSystem), or, for a consistent
 * Apply after AggregateFringe, the aggregated system P^T M_tt P's: the
 * functions covered less than FringeDropFractionOf invalid, their covered
 * integrals given to their stencils. The vectors are the operator's: they
 * live as long as it does and change only with its ShareValidity or
 * AggregateFringe.
 */
struct ProjectedSystem
{
  bool Aggregated = false;                  ///< P^T M_tt P (the fringe's aggregation), else M_tt
  const std::vector<char>* Valid = nullptr; ///< per target function: 1 if valid
  const std::vector<double>* CoveredIntegrals = nullptr; ///< per target function
  Index NumberOfValid = 0;
};

/// What one Apply() did: whether it succeeded, whether its solve was stopped, and its system.
struct ApplyResult
{
  /// False when the system could not be solved (or the solve was stopped),
  /// when the operator was built for other fields (OperatorOptions::Fields)
  /// or, for bounds, lacks M_ts.
  bool Ok = false;
  bool Stopped = false; ///< the solve was stopped (SolveOptions::Progress)
  ProjectedSystem System;
  double Seconds = 0; ///< wall clock: M_ts u_s, the solve and the bounds
  explicit operator bool() const { return this->Ok; }
};

/// Wall-clock seconds of the stages of Build() and of the last Apply().
struct OperatorTimings
{
  double Search = 0;   ///< pair search + intersections + local blocks + right-hand sides
  double Assembly = 0; ///< M_tt, M_ts from the blocks, valid functions
  double Solve = 0;    ///< the last Apply() (M_ts u_s and the solve)
};

class MortarOperator
{
public:
  MortarOperator();
  ~MortarOperator();
  MortarOperator(const MortarOperator&) = delete;
  MortarOperator& operator=(const MortarOperator&) = delete;

  /**
   * Searches the intersections and assembles M_tt and M_ts. For the
   * advancing front both meshes must have neighbours (CellNeighbors.h) and
   * `locator` must index the source cells (the brute force needs neither;
   * it may then be null). Returns false, with GetError() saying why, on
   * unusable input.
   */
  bool Build(const MeshView& target, const MeshView& source, CandidateLocator* locator,
    const OperatorOptions& options = OperatorOptions());

  /**
   * Builds several operators on the same meshes from one search (the
   * transfers of point and cell data, say): the pairs and their pieces are
   * found once and every piece goes to each operator's sums, in the order
   * its own Build would sum them, so each operator is the one its own Build
   * gives, bit for bit. Each takes its options[i] (spaces, fields, pieces
   * kept); the search's method, excluded cells, runner and progress are
   * options[0]'s, and the method and excluded cells must be the same for
   * all; at most one operator per pair of spaces. The search's time and
   * statistics: on every operator, its time on the first only. False (each
   * GetError() saying why) when any fails.
   */
  static bool BuildTogether(const std::vector<MortarOperator*>& operators,
    const std::vector<OperatorOptions>& options, const MeshView& target, const MeshView& source,
    CandidateLocator* locator);

  /**
   * After a Build() or BuildTogether() with OperatorOptions::DeferTargetMass:
   * assembles M_tt on `target` (the same target, with its geometry; its
   * neighbours and the source are no longer read), then the valid
   * functions, the covered integrals and the solver. Does nothing when they
   * are there already or the build failed.
   */
  void CompleteTargetMass(const MeshView& target);

  /**
   * Projects a source field (source functions x `components`, row-major)
   * onto the target functions (target functions x components, row-major).
   * Invalid target functions get `fill`. With solve.StartFromX the solve
   * starts from the values in targetValues (e.g. the previous step's).
   * Returns what it did (ApplyResult): Ok false when the system could not
   * be solved, or when the operator was built for other fields
   * (OperatorOptions::Fields); the system solved, whose valid functions and
   * covered integrals the values are read with (an aggregated fringe's
   * after AggregateFringe, else M_tt's).
   */
  ApplyResult Apply(const double* sourceValues, int components, double* targetValues, double fill,
    const SolveOptions& solve = SolveOptions(), const SolverHooks& hooks = SolverHooks()) const;
  /// The same with a choice of mass matrix and bounds (ApplyOptions).
  ApplyResult Apply(const double* sourceValues, int components, double* targetValues, double fill,
    const ApplyOptions& options, const SolverHooks& hooks = SolverHooks()) const;

  /**
   * A distributed system (rows of target functions shared by several parts,
   * each part built on its own target cells): makes the valid functions
   * those valid in any part. hooks.Exchange sums the diagonals of M_tt over
   * the parts sharing a row; a function covered in another part only
   * becomes valid here with an empty row (its diagonal 1 goes to 0), which
   * the other parts complete in every product. Collective: every part calls
   * it once per operator, in the same order. Default hooks: nothing changes.
   */
  void ShareValidity(const SolverHooks& hooks);

  /**
   * A well-posed fringe (FringeAggregation.h), P1 target functions of
   * any mesh (volumes, surfaces, curves, traces): the valid functions
   * whose covered fraction of their support is below `threshold` take the
   * least-squares extension of well-covered ones nearby; consistent Applies then solve P^T M_tt P u = P^T M_ts u_s.
   * After CompleteTargetMass (and ShareValidity): a distributed system
   * sums the covered and whole integrals over the parts (hooks.Exchange)
   * and, given its `halo` (the cells of the other parts within
   * FringeSearchRings rings of this part's points), extends each function as the whole target
   * would: its stencil may hold ghost points, whose rows the aggregated
   * system then has too (the halo's hooks complete them; Apply needs them
   * as ApplyOptions::FringeHooks; every part solves it when any part
   * aggregates). Without a halo each part extends from its own points.
   * Functions covered less than
   * FringeDropFractionOf are invalid in such an Apply's system (their share of
   * the covered integral goes to their stencil: ApplyResult::System), and so
   * are those with no stable stencil covered less than
   * FringeStrandedDropFraction (FringeExtension::Stranded).
   * Collective; once per operator with a positive threshold (a kept
   * operator keeps its aggregation); lumped Applies do not use it (their
   * values are means already). Returns the aggregated functions.
   */
  Index AggregateFringe(const MeshView& target, double threshold, const SolverHooks& hooks,
    const FringeHalo* halo = nullptr);
  /// The fringe's extension (empty P when nothing is aggregated).
  const FringeExtension& GetFringe() const { return this->Fringe; }

  /// Bytes held by the operator's matrices, right-hand sides and pieces.
  size_t MemoryBytes() const;
  /**
   * Per target function: int phi_i over the covered part (the row sums of
   * M_tt; invalid functions: 0). M_tt's system's, whatever the last Apply
   * solved: an aggregated solve's are in its ApplyResult::System.
   */
  const std::vector<double>& GetCoveredIntegrals() const { return this->RowSums; }

  /// M_tt over the covered part (rows of invalid functions: 1 on the diagonal).
  const CsrMatrix& GetTargetMass() const { return this->TargetMass; }
  /// M_ts: target functions x source functions (empty when built for given Fields).
  const CsrMatrix& GetMixedMass() const { return this->MixedMass; }
  /// Whether M_ts was assembled (Apply takes any field).
  bool HasMixedMass() const { return this->Options.Fields == nullptr; }
  /**
   * Gives back the matrices, the right-hand sides and the solver of an
   * operator that will not be applied again (the sizes stay); what results
   * are written from (validity, covered fractions and integrals, the
   * pieces) stays too.
   */
  void ReleaseMatrices();
  SpaceType GetTargetSpace() const { return this->Options.TargetSpace; }
  /// Whether the target functions are its second-order cells' own
  /// (NodalSpace.h): a lumped or bounded Apply then works in their
  /// Bernstein form (HasBernsteinForm), or is refused without one.
  bool HasNodalTarget() const { return this->NodalTarget; }
  /// Whether a nodal target's Bernstein form is there (every cell has one:
  /// BernsteinForm::Covers), made with M_tt.
  bool HasBernsteinForm() const { return !this->Bernstein.Empty(); }
  SpaceType GetSourceSpace() const { return this->Options.SourceSpace; }
  Index GetNumberOfTargetFunctions() const { return this->TargetMass.Rows; }
  Index GetNumberOfSourceFunctions() const { return this->SourceFunctions; }

  /**
   * Per target function: 1 if its support meets the source, else 0 (M_tt's
   * system, after ShareValidity; an aggregated solve's valid functions are
   * in its ApplyResult::System).
   */
  const std::vector<char>& GetValid() const { return this->Valid; }
  Index GetNumberOfValid() const { return this->NumberOfValid; }
  /// M_tt's system: GetValid, GetCoveredIntegrals and GetNumberOfValid as one value.
  ProjectedSystem GetAssembledSystem() const;
  /**
   * The system an Apply with `mass` solves: the aggregated one for a
   * consistent Apply after AggregateFringe aggregated any function, else
   * GetAssembledSystem().
   */
  ProjectedSystem GetSystem(MassType mass) const;
  /// Per target cell: the covered fraction of its measure (per original
  /// cell when the target's simplices have parents, once M_tt is there:
  /// CompleteTargetMass; 0 for a parent without any).
  const LargeVector<double>& GetCoveredFraction() const { return this->CoveredFraction; }
  /**
   * Per point of the target (kernel numbering), for P1 target functions:
   * the largest covered fraction (GetCoveredFraction) of the cells around
   * it, made with M_tt by CompleteTargetMass (or a Build without
   * DeferTargetMass) in the same pass over the cells. Handed over (swapped
   * with `into`, then empty here): nothing keeps it with the operator.
   * Empty for P0 target functions or once taken.
   */
  void TakePointCover(LargeVector<double>& into)
  {
    into.swap(this->PointCover);
    LargeVector<double>().swap(this->PointCover);
  }
  /// Per source cell (kernel numbering): the measure of its part the pieces
  /// cover, measured on the source cell (for surfaces and curves through
  /// the projection's Jacobian; cells left out by ExcludedSourceCells: 0).
  const LargeVector<double>& GetSourceCovered() const { return this->SourceCovered; }
  /// DP1 source functions (reconstructed cell data) and the second-order
  /// cells' own (NodalSpace.h): per function, its integral over the covered
  /// part, on the source cell as GetSourceCovered measures it; empty for
  /// the other source spaces.
  const LargeVector<double>& GetSourceFunctionCovered() const
  {
    return this->SourceFunctionCovered;
  }
  /// Target cells whose pieces add up to more than the cell (the source overlaps itself).
  Index GetNumberOfOvercoveredCells() const { return this->OvercoveredCells; }
  /// Quadrature points where a second-order target (source) cell's inverse
  /// map failed (NodalFunctions::Unconverged): its functions taken at the
  /// point's image on the simplex of its split instead.
  Index GetNumberOfUnconvergedTargetPoints() const { return this->UnconvergedPoints[0]; }
  Index GetNumberOfUnconvergedSourcePoints() const { return this->UnconvergedPoints[1]; }
  /// Area (2D) or volume (3D) of the union of all pieces: the covered part of the target.
  double GetCoveredMeasure() const { return this->CoveredMeasure; }
  const SearchStatistics& GetStatistics() const { return this->Statistics; }
  const OperatorTimings& GetTimings() const { return this->Timings; }
  const IntersectionPieces& GetPieces() const { return this->Pieces; }
  const std::string& GetError() const { return this->Error; }

private:
  template <class Intersector, class TargetSpace, class SourceSpace>
  struct Session;
  /// The session of an operator in the cells' own space (NodalSession.h).
  template <class Intersector>
  struct NodalSession;
  /// FringeValid and FringeRowSums: the dropped functions invalid, their
  /// covered integrals given to their stencils (with a halo, through its hooks).
  void DropFringe(const SolverHooks* haloHooks);
  /// The power of their covered fractions the fringe's fits on `target`
  /// weigh free points by (FitCoverage): FringeCoveragePower for point data
  /// on a linear 2D or volume target, else 0 (not weighed).
  double FitCoveragePower(const MeshView& target) const;
  /// Whether this operator sends cell data (SpaceType::P0, each source
  /// cell its constant) to the points of a linear 2D or volume target: its
  /// fringe aggregates below FringeCellDataThreshold at least and bounds
  /// its quadratic fits by FringeCellDataAmplification.
  bool CellDataFringe(const MeshView& target) const;
  /// The bound on the quadratic fits' sum |w| (FringeCellDataAmplification
  /// where CellDataFringe, else 0: the mesh's own, QuadraticAmplificationIn).
  double FitAmplification(const MeshView& target) const;
  /// AggregateFringe on a distributed system with a halo: P over the extended rows.
  void AggregateWithHalo(const MeshView& target, const std::vector<double>& fraction,
    double threshold, const FringeHalo& halo);
  /// The target and its halo as one mesh (extended rows), in `points` and `cells`.
  /// The arrays of a target joined with its halo (WithHalo).
  struct HaloMesh;
  static MeshView WithHalo(const MeshView& target, const FringeHalo& halo, HaloMesh& storage);
  // Apply's steps (MortarApply.cxx).
  /**
   * `rhs`: M_ts u_s, or the right-hand sides summed during the search (in
   * `product` when `copy`, else this->Rhs); false when built for other
   * fields.
   */
  bool RightHandSides(const double* sourceValues, int components, LargeVector<double>& product,
    bool copy, const double*& rhs) const;
  /// `product` = P^T b (over the extended rows with a halo).
  void RestrictRightHandSides(const double* b, int components, LargeVector<double>& product) const;
  /// The solve of one Apply: lumped, aggregated (with or without a halo) or plain; sets result.Stopped.
  bool Solve(const ApplyOptions& options, const double* rhs, double* targetValues, int components,
    const SolverHooks& hooks, const SolverHooks& rowHooks, ApplyResult& result) const;
  /// The lumped Apply of a nodal target in its Bernstein form, from the
  /// Bernstein functions' completed right-hand sides `rhs` (with the bounds).
  bool LumpBernstein(const ApplyOptions& options, const double* sourceValues, int components,
    const double* rhs, double* targetValues, const SolverHooks& hooks) const;
  /// ApplyOptions::Bounded after a consistent solve of `system`; false without M_ts where needed.
  bool KeepWithinBounds(const ApplyOptions& options, const ProjectedSystem& system,
    const double* sourceValues, int components, const double* rhs, double* targetValues,
    const SolverHooks& hooks) const;
  /// The aggregated solve on a distributed system with a halo (extended rows).
  bool SolveWithHalo(const double* rhs, double* targetValues, int components,
    const SolveOptions& solve, const SolverHooks& haloHooks) const;
  /// The checks of the meshes and options (Options set): false, with Error set, on unusable input.
  bool Check(const MeshView& target, const MeshView& source, CandidateLocator* locator);
  template <class Intersector>
  static void AssembleTogether(const std::vector<MortarOperator*>& operators,
    const MeshView& target, const MeshView& source, CandidateLocator* locator);

  OperatorOptions Options;
  CsrMatrix TargetMass;
  CellMasses Masses; ///< from the search until M_tt is assembled
  /// The cells' own space (NodalSpace.h) on either side: M_tt's blocks
  /// from the search until it is assembled (NodalMass.h).
  bool NodalPath = false;
  std::vector<MixedBlocks> NodalMassBlocks;
  /// The target's point functions are its cells' own (lumping is refused,
  /// the fringe measures supports by cells: NodalMass.h).
  bool NodalTarget = false;
  BernsteinForm Bernstein;  ///< a nodal target's, when every cell has one
  bool MassPending = false; ///< the search is done, M_tt not assembled yet
  CsrMatrix MixedMass;
  UninitializedLargeVector<double> Rhs; ///< M_ts u_s of OperatorOptions::Fields
  Index SourceFunctions = 0;
  std::unique_ptr<BlockCG> Solver;
  bool FringeDone = false;
  bool FringeSystem =
    false;                ///< consistent Applies solve P^T M P (with a halo: on every part alike)
  FringeExtension Fringe; ///< with a halo: over the extended rows
  Index HaloPoints = -1;  ///< the halo's ghost rows in Fringe and FringeMass (-1: no halo)
  std::vector<char> FringeValid;     ///< Valid without the dropped functions
  std::vector<double> FringeRowSums; ///< RowSums with the dropped ones' given to their stencils
  Index FringeDropped = 0;
  CsrMatrix FringeMass; ///< P^T M_tt P (when some function is aggregated)
  std::unique_ptr<BlockCG> FringeSolver;
  std::vector<char> Valid;
  std::vector<double> RowSums; ///< of M_tt, valid rows (invalid: 0)
  Index NumberOfValid = 0;
  LargeVector<double> CoveredFraction; ///< (given back to the system when replaced)
  LargeVector<double> PointCover;      ///< (until TakePointCover)
  LargeVector<double> SourceCovered;
  LargeVector<double> SourceFunctionCovered;
  double CoveredMeasure = 0;
  Index OvercoveredCells = 0;
  Index UnconvergedPoints[2] = {}; ///< target's, source's
  SearchStatistics Statistics;
  mutable OperatorTimings Timings;
  IntersectionPieces Pieces;
  std::string Error;
};
} // namespace mp

#endif
