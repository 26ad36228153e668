// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMeshProjectionFilter
 * @brief   Transfers point and cell data between two non-matching meshes by mortar L2 projection.
 *
 * vtkMeshProjectionFilter fills a target mesh (input port 0, "Input") with
 * the point and cell data of a source mesh (input port 1, "Source") such
 * that each projected field is the L2-best approximation of the source
 * field on the target (P1 on points, P0 on cells): it solves M_tt u_t = M_ts u_s, where M_tt is
 * the target mass matrix and M_ts the mixed (mortar) mass matrix, both
 * integrated exactly over the intersection polygons of every pair of source
 * and target cells. Unlike vtkResampleWithDataSet (pointwise probing), the
 * transfer is conservative (the integral of every component is preserved),
 * reproduces linear fields exactly and does not alias when the target is
 * coarser than the source.
 *
 * The intersecting cell pairs are found by the advancing front of Gander &
 * Japhet ("An algorithm for non-matching grid projections with linear
 * complexity", Domain Decomposition Methods in Science and Engineering XVIII,
 * 2009): neighbours come from the kernel's face matcher; a front starts with
 * a walk through the source, and re-seeds from bins over the source's
 * boundary cells (bins over all source cells are built only when
 * that cannot settle a cell, e.g. targets reaching beyond the source); the
 * geometry and the numerics live in a VTK-free kernel (Filters/Kernel).
 *
 * Inputs: any two datasets of the same dimension, or a trace (below) (vtkUnstructuredGrid,
 * vtkPolyData, vtkImageData, vtkRectilinearGrid, vtkStructuredGrid), or
 * composite datasets of them (vtkMultiBlockDataSet, vtkPartitionedDataSet,
 * vtkPartitionedDataSetCollection). 2D: triangles, quads, pixels, polygons
 * and triangle strips lying in one plane, any plane (2D meshes with 3D
 * coordinates; planarity is judged relative to the mesh's size). Surfaces
 * in 3D: the same cells not in one plane (two facetizations of a curved
 * surface, an interface, a contact pair): each Source facet is projected
 * onto the Input facet's plane along its normal and intersected there, the
 * integrals taken on the Input facets; facets meet within SurfaceReach and
 * with oriented normals within MaximumNormalAngle (both meshes must be
 * consistently oriented); a planar mesh matched with a surface is one too,
 * two planar meshes stay the 2D case. 3D:
 * tetrahedra, hexahedra, voxels, wedges, pyramids, pentagonal and hexagonal
 * prisms and polyhedra. Cell types may be mixed. The meshes need not cover
 * the same region, be connected or convex. Traces: a surface (planar or
 * not) or a curve inside a 3D Source, or a curve inside a 2D Source in its
 * plane: each Input facet or segment is cut by the Source's cells, and the
 * volume field is projected onto the surface or curve (where it lies
 * inside; only TargetIntegral_ is reported, and extensive cell data stay
 * densities).
 *
 * Cells that are not simplices are split into triangles or tetrahedra on
 * their own points, by a rule on the point ids that splits a face shared by
 * two cells the same way on both sides (each polygonal face is fanned from
 * its lowest-numbered point, each 3D cell is the cone from its
 * lowest-numbered point over the faces away from it; see
 * Kernel/Geometry/CellSplit.h). Point data is therefore projected onto the
 * continuous piecewise linear functions on that split, with one value per
 * original point (linear fields stay exact, integrals are conserved), and
 * cell data onto one constant per original cell. A non-convex 3D cell is
 * coned from another corner it is star-shaped from (across its faces
 * through that corner the field may then be discontinuous); a cell
 * star-shaped from none of its corners (inverted, twisted or strongly
 * non-convex) is an error.
 * Cells of lower dimension than the mesh (vertices, lines, the faces of a
 * volume mesh) are left out with a warning (no cell values there);
 * nonlinear cells (quadratic, Lagrange, ...) are an error that names
 * Tessellate.
 *
 * Composite inputs. A composite Source is one mesh made of all its dataset
 * blocks (their arrays in common; blocks meeting at an interface give the
 * result of the merged mesh). A composite Input is projected block by
 * block: each block is a mesh of its own with its own points and its own
 * system M_tt u_t = M_ts u_s (a point on an interface of two blocks exists
 * in both and gets each block's value; for a continuous field the two
 * agree up to the projection's error, not exactly). Output 0 has Input's
 * block structure; blocks that are empty or not datasets are skipped, a
 * block that cannot be projected (another dimension, another plane) is
 * passed through with a warning. Operators are kept per block.
 *
 * What is projected, and onto what (all Source arrays by default):
 *  - point arrays (PointDataArraySelection) are P1 fields: continuous,
 *    piecewise linear on the cells. They go to Input's points (default),
 *    cells (the L2 projection onto piecewise constants: each cell's mean of
 *    the source field over its covered part), or both (PointDataTarget).
 *  - cell arrays (CellDataArraySelection) are P0 fields: one value per
 *    cell. They go to Input's cells (default), points, or both
 *    (CellDataTarget). Cell to cell is the measure-weighted mean over the
 *    covered part (exact on constants, conservative). CellDataQuantity
 *    says what the values are: INTENSIVE (default: densities, temperatures,
 *    velocities; a value per unit area or volume) or EXTENSIVE (totals:
 *    mass, counts, sums), whose projection keeps totals: each target cell
 *    gets the sum of the source totals times the covered fraction of each
 *    source cell it meets (to points: the projected density, the total per
 *    unit area or volume).
 * MassMatrix CONSISTENT (default) is the L2 projection; LUMPED divides by
 * the row sums instead (never leaves the range of the source values on a
 * target function's support, no solve, but only first order). With
 * PreserveBounds the consistent projection is clipped to those local
 * ranges and the clipped integral given back (clip and assured sum): no
 * overshoot, integral conserved, linear fields still exact.
 *
 * Output port 0: a shallow copy of Input (of its type) with, for each projected array, a
 * vtkDoubleArray of the same name and components (an Input array of the
 * same name is replaced; a point array projected to cells next to a cell
 * array of the same name gets the suffix " (from points)", and likewise
 * " (from cells)"), plus
 *  - "vtkValidPointMask" (char point array): 1 where the point's support
 *    meets the source, else 0; invalid points get NaN (or FillValue);
 *  - "vtkValidCellMask" (char cell array, when arrays go to cells): 1 where
 *    the cell meets the source; invalid cells get NaN (or FillValue);
 *  - "CoveredFraction" (double cell array): the fraction of each target
 *    cell's area (volume) covered by the source;
 *  - field data "SourceIntegral_<array>" (the Source field's integral over
 *    the part of Source the pieces cover) and "TargetIntegral_<array>" (the
 *    projection's over the covered target, equal to the projected Source
 *    field's; for surfaces they differ as the facetizations' areas do, see
 *    ConserveSourceIntegral); cell arrays' names end in " (cell data)".
 * Missing values: a NaN or infinite value in a Source array leaves the
 * Source cells that use it out of that array's projection (a hole in
 * Source for that array only, with an operator of its own; conservation
 * holds on the rest of the common part). Targets left without data get the
 * fill value and are marked in the masks above when every projected array
 * agrees, else in "vtkValidPointMask_<array>" / "vtkValidCellMask_<array>".
 * Corrupt input (ids outside the points, bad offsets, face streams or cell
 * types, a short ghost array) is an error naming the first bad cell, before
 * any cell is read; the output is then Input passed through. Source arrays
 * shorter than the points (cells) are skipped with a warning.
 * When OutputIntersections is on:
 *  - output port 1 (2D inputs, surfaces, curves, traces): the intersection
 *    polygons (for surfaces on the target facets, in 3D), vtkPolyData with
 *    cell arrays "SourceCellId", "TargetCellId" (vtkIdType) and "Area"; for
 *    curves segments, with "Length";
 *  - output port 2 (3D inputs): the intersection polyhedra as their
 *    tetrahedral decomposition, vtkUnstructuredGrid with cell arrays
 *    "SourceCellId", "TargetCellId" and "Volume" (of each tetrahedron).
 * The port not used by the inputs' dimension stays empty. SourceCellId
 * and TargetCellId are the ids of the original cells (a split cell's
 * pieces all name it); for a composite Input the pieces of all blocks are
 * appended, with a "TargetBlock" cell array (the block's flat index).
 *
 * Time: the output advertises the time steps of both inputs (their union)
 * and asks both for the requested time, so a time-varying Source (or
 * Input) is followed. With CacheOperator on (default) the operators (the
 * matrices M_tt and M_ts of each transfer used) are kept between
 * executions and reused while neither mesh changed (same points, cells and
 * cell types, compared by a 64-bit fingerprint of their arrays' contents,
 * since readers build new arrays at every step): a step then costs the
 * right-hand sides and a solve started from the previous step's solution.
 * A one-off run does not form M_ts (the right-hand sides are summed during
 * the search): the operators are assembled when an input advertises time
 * steps, when the meshes of the last execution come again, when
 * PreserveBounds needs M_ts, or when GetMatrix() asks for it.
 * OperatorReused tells whether the last execution reused them;
 * OperatorMemory their size. GetMatrix() gives the kept matrices as
 * compressed rows and WriteMatrixMarket() writes them.
 *
 * Progress is reported through the stages, and AbortExecute stops a run
 * (polled in the search every 8192 target cells): the output is then Input
 * as it came, with a warning.
 *
 * Non-numeric Source arrays (strings, variants) are skipped with a
 * warning; integer arrays are projected as real values, with a warning (an
 * L2 projection of labels or ids is not meaningful). Invalid input (no
 * Source, nonlinear cells, cells that cannot be split, an Input of a
 * higher dimension than Source, a curve off a 2D Source's plane, NaN/Inf
 * coordinates)
 * produces an error and an output that is a plain copy of Input; empty
 * meshes and meshes that do not overlap give a warning and invalid points.
 *
 * Threads: the search, the intersections and the local integrals run in one
 * task per vtkSMPTools thread (ranges of target cells, each with its own
 * advancing front); results equal the serial ones up to summation order.
 * The filter runs them in its own vtkSMPTools scope with NumberOfThreads
 * threads (0, the default: every core), on STDThread when VTK's backend is
 * the sequential one (Debian's default); the application's backend is left
 * as it was.
 *
 * @sa vtkResampleWithDataSet vtkProbeFilter
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
    MIXED_MASS = 1   ///< M_ts (target functions x source functions)
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
   * a 1 on the diagonal. When the last execution was a one-off run (M_ts
   * not formed), the filter executes once more, assembling it. Returns the
   * number of columns, or -1 (with an error) when no such operator can be
   * had: CacheOperator off, no inputs, or the transfer not in use.
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
  int PointDataTarget = TO_POINTS;
  int CellDataTarget = TO_CELLS;
  int CellDataQuantity = INTENSIVE;
  int MassMatrix = CONSISTENT_MASS;
  bool PreserveBounds = false;
  int MaximumIterations = 500;
  double SurfaceReach = 0.5;
  double MaximumNormalAngle = 45.0;
  int NormalOrientation = SAME_ORIENTATION;
  bool ConserveSourceIntegral = false;
  bool CacheOperator = true;
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
