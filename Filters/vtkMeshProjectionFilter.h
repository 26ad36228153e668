// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMeshProjectionFilter
 * @brief   Transfers point and cell data between two non-matching meshes by mortar L2 projection.
 *
 * Fills Input (port 0, the target) with the point and cell arrays of Source
 * (port 1, SetSourceConnection/SetSourceData) so that each projected field
 * is the L2-best approximation of the Source field on the part of Input the
 * Source covers: M_tt u_t = M_ts u_s, both mass matrices integrated exactly
 * over the intersection pieces of every pair of cells. Every field's
 * integral is conserved and linear fields are reproduced exactly; unlike
 * vtkResampleWithDataSet (pointwise probing) a coarse target does not alias.
 * Intersecting pairs are found by the linear-complexity advancing front of
 * Gander & Japhet (2009), with exact predicates; the geometry and numerics
 * live in a VTK-free kernel (Filters/Kernel).
 *
 * Inputs: any vtkDataSet or composite dataset of them, of the same
 * dimension (curves, 2D in any plane, surfaces in 3D, volumes), or a trace
 * (a surface or curve inside a volume Source). Cells that are not simplices
 * are split on their own points. Point data is a P1 field, cell data P0;
 * PointDataTarget and CellDataTarget say where each goes, CellDataQuantity
 * whether cell values are intensive or extensive, MassMatrix and
 * PreserveBounds how the projection is bounded. Where Input reaches beyond
 * Source, point values covered in slivers take the extension of
 * well-covered ones (FringeThreshold), and Extrapolation fills the values
 * beyond (vtkExtrapolatedPointMask / vtkExtrapolatedCellMask).
 *
 * Output 0: Input with a double array per projected Source array, the
 * masks vtkValidPointMask / vtkValidCellMask (and per-array masks when
 * NaN holes differ), CoveredFraction, and field data SourceIntegral_<array>
 * and TargetIntegral_<array>. With OutputIntersections, output 1 holds the
 * intersection polygons or segments and output 2 the polyhedra as
 * tetrahedra. The output follows the time steps of both inputs; with
 * CacheOperator the operators are kept while neither mesh changes, and
 * GetMatrix() / WriteMatrixMarket() export them. Invalid input gives an
 * error naming the cell and passes Input through.
 *
 * Every property, output, warning and error, with defaults and when to
 * change them: docs/user-guide.md. The method: docs/method.md.
 * vtkPMeshProjectionFilter runs the same on several MPI processes.
 *
 * @sa vtkPMeshProjectionFilter vtkResampleWithDataSet vtkProbeFilter
 */
#ifndef vtkMeshProjectionFilter_h
#define vtkMeshProjectionFilter_h

#include "MeshProjectionFiltersModule.h" // for export macro
#include "vtkPassInputTypeAlgorithm.h"

#include <string> // for ReportSkipped
#include <vector> // for ReportSkipped

class vtkDataArraySelection;
class vtkDataSet;
namespace mpvtk
{
class Messages;
class Parts;
class StageClock;
struct Settings;
struct Statistics;
struct Verdict;
}
class vtkDoubleArray;
class vtkIdTypeArray;

class MESHPROJECTIONFILTERS_EXPORT vtkMeshProjectionFilter : public vtkPassInputTypeAlgorithm
{
public:
  static vtkMeshProjectionFilter* New();
  vtkTypeMacro(vtkMeshProjectionFilter, vtkPassInputTypeAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum SearchMethods
  {
    ADVANCING_FRONT = 0, ///< Gander & Japhet's front over neighbours: linear complexity
    BRUTE_FORCE = 1      ///< every target cell against every source cell: O(n m), for checks
  };

  /// Where projected arrays go (PointDataTarget, CellDataTarget).
  enum Targets
  {
    TO_POINTS = 1,
    TO_CELLS = 2,
    TO_POINTS_AND_CELLS = 3
  };
  /// What the values of cell arrays are (CellDataQuantity).
  enum Quantities
  {
    INTENSIVE = 0, ///< per unit area or volume: means are projected
    EXTENSIVE = 1  ///< totals per cell: totals are kept
  };
  /// How cell arrays are seen on each Source cell (CellDataReconstruction).
  enum Reconstructions
  {
    CONSTANT_RECONSTRUCTION = 0,  ///< the cell's value (first order)
    LIMITED_RECONSTRUCTION = 1,   ///< linear, limited: second order, no new extrema in cells
    UNLIMITED_RECONSTRUCTION = 2  ///< linear: second order, exact for linear fields
  };
  enum MassMatrices
  {
    CONSISTENT_MASS = 0, ///< the L2 projection
    LUMPED_MASS = 1      ///< row sums: bounded, first order
  };
  /// The four operators (GetMatrix, WriteMatrixMarket): source -> target spaces.
  enum Transfers
  {
    POINTS_TO_POINTS = 0,
    POINTS_TO_CELLS = 1,
    CELLS_TO_CELLS = 2,
    CELLS_TO_POINTS = 3
  };
  enum Matrices
  {
    TARGET_MASS = 0, ///< M_tt (target functions x target functions)
    MIXED_MASS = 1,  ///< M_ts (target functions x source functions)
    FRINGE_EXTENSION = 2, ///< P, target functions x target functions (FringeThreshold): u = P u_free
    EXTRAPOLATION = 3     ///< E, target functions x target functions (Extrapolation): output = E u
  };

  ///@{
  /**
   * The mesh carrying the data to project (input port 1), as in
   * vtkResampleWithDataSet.
   */
  void SetSourceConnection(vtkAlgorithmOutput* algOutput);
  void SetSourceData(vtkDataObject* source);
  vtkDataObject* GetSource();
  ///@}

  ///@{
  /**
   * How intersecting cell pairs are found. Both give the same pairs; the
   * brute force exists for verification and comparison.
   * Default: ADVANCING_FRONT.
   */
  vtkSetClampMacro(SearchMethod, int, ADVANCING_FRONT, BRUTE_FORCE);
  vtkGetMacro(SearchMethod, int);
  void SetSearchMethodToAdvancingFront() { this->SetSearchMethod(ADVANCING_FRONT); }
  void SetSearchMethodToBruteForce() { this->SetSearchMethod(BRUTE_FORCE); }
  ///@}

  ///@{
  /**
   * Whether output port 1 (2D) or 2 (3D) receives the intersection pieces.
   * Default: false (both stay empty).
   */
  vtkSetMacro(OutputIntersections, bool);
  vtkGetMacro(OutputIntersections, bool);
  vtkBooleanMacro(OutputIntersections, bool);
  ///@}

  ///@{
  /**
   * What target points whose support does not meet the source receive:
   * NaN when FillWithNaN is on (default: true), else FillValue
   * (default: 0). vtkValidPointMask marks them either way.
   */
  vtkSetMacro(FillWithNaN, bool);
  vtkGetMacro(FillWithNaN, bool);
  vtkBooleanMacro(FillWithNaN, bool);
  vtkSetMacro(FillValue, double);
  vtkGetMacro(FillValue, double);
  ///@}

  ///@{
  /**
   * What target points and cells the Source does not reach receive instead
   * of the fill value: NO_EXTRAPOLATION (default), SMOOTH_EXTRAPOLATION (a
   * creep fill: layer by layer over Input's point graph, or cell graph for
   * cell data, each the weighted mean of its neighbours already reached:
   * within the valid values' range, no new extrema) or
   * NEAREST_EXTRAPOLATION (the value of the nearest valid point or cell
   * along Input's graph). vtkExtrapolatedPointMask and
   * vtkExtrapolatedCellMask mark them; parts of Input connected to no valid
   * point keep the fill value. The valid values are then kept within the
   * Source field's range (a clip and assured sum: the integral stays;
   * intensive data). Both extensions are linear: GetMatrix EXTRAPOLATION.
   */
  enum Extrapolations { NO_EXTRAPOLATION = 0, SMOOTH_EXTRAPOLATION = 1, NEAREST_EXTRAPOLATION = 2 };
  vtkSetClampMacro(Extrapolation, int, NO_EXTRAPOLATION, NEAREST_EXTRAPOLATION);
  vtkGetMacro(Extrapolation, int);
  ///@}

  ///@{
  /**
   * A well-posed fringe: point values whose support the Source covers less
   * than this fraction (default 0.25) take the least-squares extension of
   * well-covered points nearby instead of being fitted to a sliver; those
   * covered less than 2% become invalid (docs/method.md); 0 turns it off.
   */
  vtkSetClampMacro(FringeThreshold, double, 0.0, 0.9);
  vtkGetMacro(FringeThreshold, double);
  ///@}

  ///@{
  /**
   * Which Source point and cell arrays are projected. Arrays not listed
   * are enabled (all arrays by default); disable them by name, e.g.
   * GetPointDataArraySelection()->DisableArray("p"). The filter lists
   * Source's arrays in them as it sees them (for ParaView's panel).
   */
  vtkDataArraySelection* GetPointDataArraySelection();
  vtkDataArraySelection* GetCellDataArraySelection();
  ///@}

  ///@{
  /**
   * ParaView's array lists (the PointDataArrays and CellDataArrays
   * properties): each change of a list clears the selection, then states
   * the status of each array the list names. A list naming every array the
   * filter had listed (the panel's) leaves arrays that appear later
   * projected; a list naming fewer (a script that named arrays before
   * Source had run, when the list could not know the others) projects
   * only what it enables; a list naming none, all. (Through the
   * selections' own calls above, arrays not listed stay enabled.)
   */
  void ClearPointDataArrayStatuses();
  void SetPointDataArrayStatus(const char* name, int status);
  void ClearCellDataArrayStatuses();
  void SetCellDataArrayStatus(const char* name, int status);
  ///@}

  ///@{
  /**
   * Where Source point arrays go (TO_POINTS: default) and where Source cell
   * arrays go (TO_CELLS: default); TO_POINTS_AND_CELLS gives both.
   */
  vtkSetClampMacro(PointDataTarget, int, TO_POINTS, TO_POINTS_AND_CELLS);
  vtkGetMacro(PointDataTarget, int);
  vtkSetClampMacro(CellDataTarget, int, TO_POINTS, TO_POINTS_AND_CELLS);
  vtkGetMacro(CellDataTarget, int);
  ///@}

  ///@{
  /**
   * INTENSIVE (default) or EXTENSIVE cell arrays (see the class
   * description). Point arrays are always fields (intensive).
   */
  vtkSetClampMacro(CellDataQuantity, int, INTENSIVE, EXTENSIVE);
  vtkGetMacro(CellDataQuantity, int);
  ///@}

  ///@{
  /**
   * How a Source cell array is seen on each Source cell before it is
   * projected. CONSTANT_RECONSTRUCTION (default): the cell's value (first
   * order). LIMITED_RECONSTRUCTION: a linear function with the cell's mean,
   * its gradient fitted to the neighbouring cells' values and limited so
   * that no value leaves the range of the cell and its neighbours (second
   * order; to cells, no new extrema). UNLIMITED_RECONSTRUCTION: the same without the
   * limiter (second order, exact for linear fields). Integrals are kept in
   * every mode; extensive arrays are reconstructed as densities.
   */
  vtkSetClampMacro(CellDataReconstruction, int, CONSTANT_RECONSTRUCTION, UNLIMITED_RECONSTRUCTION);
  vtkGetMacro(CellDataReconstruction, int);
  ///@}

  ///@{
  /**
   * CONSISTENT_MASS (default): the L2 projection; LUMPED_MASS: bounded and
   * cheap, first order.
   */
  vtkSetClampMacro(MassMatrix, int, CONSISTENT_MASS, LUMPED_MASS);
  vtkGetMacro(MassMatrix, int);
  ///@}

  ///@{
  /**
   * Keeps each projected value within the range of the source values on its
   * support, conserving the integral (clip and assured sum after the
   * consistent projection). Default: false.
   */
  vtkSetMacro(PreserveBounds, bool);
  vtkGetMacro(PreserveBounds, bool);
  vtkBooleanMacro(PreserveBounds, bool);
  ///@}

  ///@{
  /**
   * The most conjugate-gradient iterations per solve of the consistent mass
   * matrix (to a relative residual of 1e-14); fields still unconverged then
   * go to the sparse direct solver (LDL^T; on several processes the whole
   * system gathered on process 0). 0: the direct solver only. Default 500
   * (a mass matrix needs about 25; many more only where targets are
   * covered in slivers).
   */
  vtkSetClampMacro(MaximumIterations, int, 0, 1000000);
  vtkGetMacro(MaximumIterations, int);
  ///@}

  ///@{
  /**
   * Surfaces in 3D (triangles, quads or polygons not in one plane; see the
   * class description). SurfaceReach: the largest distance between a source
   * facet and a target facet's plane at which they still meet, relative to
   * the target facet's longest edge (default 0.5: two facetizations of one
   * curved surface are much closer, O(h^2 / R); a small gap between two
   * solvers' interfaces is bridged; at most 100). MaximumNormalAngle: the largest angle
   * in degrees between the two facets' normals (default 45, at most 89),
   * oriented: the two sides of a thin plate or shell, and the faces meeting
   * at a sharp edge, are never matched. Both meshes must be consistently
   * oriented (as mesh generators write them; vtkPolyDataNormals can fix
   * others).
   */
  vtkSetClampMacro(SurfaceReach, double, 0.0, 100.0);
  vtkGetMacro(SurfaceReach, double);
  vtkSetClampMacro(MaximumNormalAngle, double, 0.0, 89.0);
  vtkGetMacro(MaximumNormalAngle, double);
  ///@}

  enum
  {
    SAME_ORIENTATION = 0,
    OPPOSITE_ORIENTATION = 1,
    ANY_ORIENTATION = 2
  };
  ///@{
  /**
   * Surfaces: how the two meshes' normals are compared with
   * MaximumNormalAngle. SAME_ORIENTATION (default): as they are, for two
   * facetizations of one surface oriented alike. OPPOSITE_ORIENTATION: one
   * reversed, for two bodies' boundaries facing each other (contact,
   * fluid-structure interaction: each side's outward normals point into the
   * other). ANY_ORIENTATION: either way, for meshes whose orientation is
   * unknown or inconsistent; then only SurfaceReach keeps the two sides of a
   * thin plate or shell apart.
   */
  vtkSetClampMacro(NormalOrientation, int, SAME_ORIENTATION, ANY_ORIENTATION);
  vtkGetMacro(NormalOrientation, int);
  ///@}

  ///@{
  /**
   * Scales each projected array (each component, its valid values) so that
   * its integral over the covered target equals the Source field's integral
   * over the covered part of Source ("SourceIntegral_<name>", field data),
   * instead of the integral of the projected Source field (conservation on
   * the target). Meant for
   * surfaces, whose two facetizations differ in area: loads and fluxes then
   * keep their totals exactly. A component whose two integrals differ by
   * more than a factor of 2 (or with a zero integral) is left unscaled, with
   * a warning. Linear fields are then no longer exact. Default: false.
   */
  vtkSetMacro(ConserveSourceIntegral, bool);
  vtkGetMacro(ConserveSourceIntegral, bool);
  vtkBooleanMacro(ConserveSourceIntegral, bool);
  ///@}

  ///@{
  /**
   * Threads for the filter's parallel loops (the search, the intersections
   * and local integrals, the assembly, the solve, the neighbours): 0
   * (default) uses every core. The filter runs them in a local vtkSMPTools
   * scope, on the STDThread backend when VTK's own is the sequential one
   * (Debian's default), so ParaView, pvpython and VTK programs get every core
   * without setting VTK_SMP_BACKEND_IN_USE. 1: the calling thread only.
   * Results depend on the number of threads only through summation order.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  enum
  {
    AUTOMATIC_RENUMBERING = 0,
    ALWAYS_RENUMBER = 1,
    NEVER_RENUMBER = 2
  };
  ///@{
  /**
   * How the meshes are numbered inside the filter. AUTOMATIC_RENUMBERING
   * (default): a mesh whose numbering does not follow space (shuffled
   * cells or points, a partitioner's order, a Delaunay mesher's points in
   * insertion order) is renumbered along a space-filling (Morton) curve, in a copy, so that
   * the time does not depend on how the input is numbered; a mesh numbered
   * with locality (a sweep, a mesh generator's renumbering) is used as it
   * is. With more than one thread, a mesh whose cells seldom have a face
   * neighbour among the cells numbered next to them (interleaved sweeps) is
   * renumbered too, since the threads take ranges of ids. ALWAYS_RENUMBER and
   * NEVER_RENUMBER force either. The outputs are in
   * the datasets' own numbering in every case, and equal up to summation
   * order.
   */
  vtkSetClampMacro(Renumbering, int, AUTOMATIC_RENUMBERING, NEVER_RENUMBER);
  vtkGetMacro(Renumbering, int);
  ///@}

  ///@{
  /**
   * Keeps the operators between executions and reuses them while neither
   * mesh changes (time series on fixed meshes). Default: true. Off, each
   * execution builds what it needs (M_ts only for PreserveBounds) and keeps
   * nothing: no memory held between executions, no matrices to read out.
   */
  vtkSetMacro(CacheOperator, bool);
  vtkGetMacro(CacheOperator, bool);
  vtkBooleanMacro(CacheOperator, bool);
  ///@}

  ///@{
  /**
   * Makes every execution form M_ts and, with CacheOperator, keep the
   * operators, so that GetMatrix can read them. Default: false: an
   * execution that is not part of a time series (nor a repeat on the same
   * meshes, nor with PreserveBounds) sums its fields' right-hand sides
   * during the search instead, which saves M_ts's time and memory, and
   * keeps no operator. Set it before the Update whose matrices you want
   * (the Python helpers meshprojection.operator_matrices and the others do).
   */
  vtkSetMacro(KeepMatrices, bool);
  vtkGetMacro(KeepMatrices, bool);
  vtkBooleanMacro(KeepMatrices, bool);
  ///@}

  ///@{
  /**
   * Whether the last execution reused the kept operators (no search, no
   * assembly), how many operators it built, and the bytes the kept
   * operators hold.
   */
  vtkGetMacro(OperatorReused, bool);
  vtkGetMacro(NumberOfOperatorsBuilt, int);
  vtkIdType GetOperatorMemory();
  ///@}

  /**
   * The kept operator of a transfer (POINTS_TO_POINTS, ...) as compressed
   * sparse rows: row i holds columns[rowStart[i]..rowStart[i+1]) and their
   * values. Rows are Input's points or cells, columns Input's (TARGET_MASS)
   * or Source's (MIXED_MASS) points or cells, in VTK ids (for a composite
   * Input: the first block's; a composite Source's columns number the
   * points or cells of its blocks one block after the other). M_tt is
   * integrated over the covered part; rows of invalid target functions hold
   * a 1 on the diagonal. FRINGE_EXTENSION is the fringe's
   * extension P: the consistent result is u = P x with
   * (P^T M_tt P) x = P^T M_ts u_s on P's nonzero columns (the identity
   * without an aggregated fringe, and for cells). EXTRAPOLATION is the
   * extension E of the valid values (Extrapolation): the output is E u on
   * rows that are not empty, the fill value on empty ones (without
   * Extrapolation: the identity on valid rows); one process's rows.
   * With Extrapolation the valid values are also kept within the Source
   * field's range (clip and assured sum), which no matrix holds: the
   * matrices reproduce the output where that range is not reached (a
   * linear field, for one).
   *
   * GetMatrix reads what the last execution kept; it never executes the
   * filter. Returns the number of columns, or -1 (with an error) when no
   * such operator can be had: the filter has not executed, or it or its
   * inputs changed since (call Update() first), or nothing was kept
   * (CacheOperator off, KeepMatrices off on a one-off execution, the
   * transfer not in use). So: SetKeepMatrices(true), Update(), GetMatrix().
   * On several processes (vtkPMeshProjectionFilter) it is not collective:
   * each process reads its own rows, and may call it alone.
   */
  vtkIdType GetMatrix(int transfer, int matrix, vtkIdTypeArray* rowStart,
    vtkIdTypeArray* columns, vtkDoubleArray* values);
  /// Writes GetMatrix()'s matrix as a Matrix Market coordinate file (1-based); false on failure.
  bool WriteMatrixMarket(const char* fileName, int transfer, int matrix);

  ///@{
  /**
   * Results of the last execution (summed over the blocks of a composite
   * Input): intersecting simplex pairs with an intersection of positive
   * measure, simplex-pair intersection tests, locator queries (among the
   * source's boundary cells or all its cells), the covered area (2D) or
   * volume (3D) of the target, and the wall-clock seconds of the whole
   * execution.
   */
  vtkGetMacro(NumberOfIntersections, vtkIdType);
  vtkGetMacro(NumberOfIntersectionTests, vtkIdType);
  vtkGetMacro(NumberOfLocatorQueries, vtkIdType);
  vtkGetMacro(CoveredMeasure, double);
  vtkGetMacro(ExecutionTime, double);
  ///@}

  ///@{
  /**
   * Wall-clock seconds of the stages of the last execution: reading the
   * inputs (cell types, the split of cells that are not simplices,
   * coordinate checks, the fields gathered), the cell
   * neighbours, the locator over the source's boundary
   * cells (bins of their boxes), the pair search with the intersections and
   * local integrals (and a locator over all source cells, when one is
   * needed), the assembly (M_tt, and the Source's covered integrals that
   * the conservation figures compare with), the solve, and writing the
   * outputs.
   */
  vtkGetMacro(InputTime, double);
  /// Of InputTime: checking both meshes' ids, offsets, types and face
  /// streams before any cell is read (CheckDataSet).
  vtkGetMacro(CheckTime, double);
  /// Of InputTime: renumbering the meshes along space (see Renumbering;
  /// 0 when neither was renumbered).
  vtkGetMacro(RenumberTime, double);
  /// How many of the two meshes (of the last leaf of a composite Input:
  /// Source and that leaf) the last execution renumbered.
  vtkGetMacro(NumberOfRenumberedMeshes, int);
  vtkGetMacro(NeighborsTime, double);
  vtkGetMacro(LocatorTime, double);
  vtkGetMacro(SearchTime, double);
  vtkGetMacro(AssemblyTime, double);
  vtkGetMacro(SolveTime, double);
  vtkGetMacro(OutputTime, double);
  ///@}

protected:
  vtkMeshProjectionFilter();
  ~vtkMeshProjectionFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// RequestData inside the filter's own vtkSMPTools scope (NumberOfThreads).
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

  int SearchMethod = ADVANCING_FRONT;
  bool OutputIntersections = false;
  bool FillWithNaN = true;
  double FillValue = 0;
  int Extrapolation = NO_EXTRAPOLATION;
  double FringeThreshold = 0.25;
  int PointDataTarget = TO_POINTS;
  int CellDataTarget = TO_CELLS;
  int CellDataQuantity = INTENSIVE;
  int CellDataReconstruction = CONSTANT_RECONSTRUCTION;
  int MassMatrix = CONSISTENT_MASS;
  bool PreserveBounds = false;
  int MaximumIterations = 500;
  double SurfaceReach = 0.5;
  double MaximumNormalAngle = 45.0;
  int NormalOrientation = SAME_ORIENTATION;
  bool ConserveSourceIntegral = false;
  bool CacheOperator = true;
  bool KeepMatrices = false;
  int NumberOfThreads = 0;
  int Renumbering = AUTOMATIC_RENUMBERING;
  bool OperatorReused = false;
  int NumberOfOperatorsBuilt = 0;

  vtkIdType NumberOfIntersections = 0;
  vtkIdType NumberOfIntersectionTests = 0;
  vtkIdType NumberOfLocatorQueries = 0;
  double CoveredMeasure = 0;
  double ExecutionTime = 0;
  double InputTime = 0;
  double CheckTime = 0;
  double RenumberTime = 0;
  int NumberOfRenumberedMeshes = 0;
  double NeighborsTime = 0;
  double LocatorTime = 0;
  double SearchTime = 0;
  double AssemblyTime = 0;
  double SolveTime = 0;
  double OutputTime = 0;

  /// The processes of a distributed run (vtkPMeshProjectionFilter sets it
  /// during RequestData); null: serial.
  /// The processes' seam (Parallel/Parts.h): installed by vtkPMeshProjectionFilter while it
  /// runs on several processes; null, one process (mpvtk::SerialParts).
  mpvtk::Parts* Parts = nullptr;

private:
  vtkMeshProjectionFilter(const vtkMeshProjectionFilter&) = delete;
  void SelectionModified();
  void ListSource(vtkDataObject* source);
  mpvtk::Settings CurrentSettings() const;
  mpvtk::Verdict Project(vtkInformationVector** inputVector, vtkInformationVector* outputVector,
    mpvtk::Parts& parts, mpvtk::StageClock& clock, mpvtk::Statistics& stats);
  void ReportSkipped(const std::vector<std::string>& skipped, size_t leaves, int projected,
    mpvtk::Messages& say);
  void Publish(const mpvtk::Statistics& stats, double seconds);
  struct Internals;
  Internals* Internal;
  void operator=(const vtkMeshProjectionFilter&) = delete;
};

#endif
