// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMeshProjectionFilter
 * @brief   Transfers point and cell data between two non-matching meshes by mortar L2 projection.
 *
 * Fills Input (port 0, the target) with the point and cell arrays of Source
 * (port 1) so that each projected field is the L2-best approximation of the
 * Source field on the part of Input the Source covers: M_tt u_t = M_ts u_s,
 * both mass matrices integrated exactly over the intersections of the two
 * meshes' cells. Integrals are conserved and linear fields reproduced;
 * unlike vtkResampleWithDataSet (pointwise probing) a coarse target does
 * not alias. Inputs: any vtkDataSet or composite dataset, curves, 2D,
 * surfaces in 3D, volumes, or a surface or curve inside a volume Source.
 *
 * Output 0 is Input with a double array per projected Source array (a
 * label array keeps its type: CategoricalMode), the
 * masks vtkValidPointMask / vtkValidCellMask, CoveredFraction, and the
 * field data SourceIntegral_<array> and TargetIntegral_<array>; outputs 1
 * and 2 the intersection pieces (OutputIntersections). Invalid input gives
 * an error naming the cell and passes Input through.
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

#include <string> // for DensityArray

class vtkDataArraySelection;
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
    CONSTANT_RECONSTRUCTION = 0, ///< the cell's value (first order)
    LIMITED_RECONSTRUCTION = 1,  ///< linear, limited: second order, no new extrema in cells
    UNLIMITED_RECONSTRUCTION = 2 ///< linear: second order, exact for linear fields
  };
  /// Which Source arrays are labels (CategoricalMode).
  enum CategoricalModes
  {
    CATEGORICAL_AUTOMATIC = 0, ///< single-component integer arrays
    CATEGORICAL_SELECTED = 1   ///< exactly the arrays named in CategoricalArrays
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
    FRINGE_EXTENSION =
      2,              ///< P, target functions x target functions (FringeThreshold): u = P u_free
    EXTRAPOLATION = 3 ///< E, target functions x target functions (Extrapolation): output = E u
  };

  ///@{
  /// The mesh carrying the data to project (input port 1), as in vtkResampleWithDataSet.
  void SetSourceConnection(vtkAlgorithmOutput* algOutput);
  void SetSourceData(vtkDataObject* source);
  vtkDataObject* GetSource();
  ///@}

  ///@{
  /**
   * How intersecting cell pairs are found; both give the same pairs, the
   * brute force is for checks. Default: ADVANCING_FRONT.
   */
  vtkSetClampMacro(SearchMethod, int, ADVANCING_FRONT, BRUTE_FORCE);
  vtkGetMacro(SearchMethod, int);
  void SetSearchMethodToAdvancingFront() { this->SetSearchMethod(ADVANCING_FRONT); }
  void SetSearchMethodToBruteForce() { this->SetSearchMethod(BRUTE_FORCE); }
  ///@}

  ///@{
  /// Whether output port 1 (2D) or 2 (3D) receives the intersection pieces. Default: false.
  vtkSetMacro(OutputIntersections, bool);
  vtkGetMacro(OutputIntersections, bool);
  vtkBooleanMacro(OutputIntersections, bool);
  ///@}

  ///@{
  /**
   * What target points and cells the Source does not reach receive: NaN
   * when FillWithNaN is on (default: true), else FillValue (default: 0).
   * vtkValidPointMask and vtkValidCellMask mark them either way.
   */
  vtkSetMacro(FillWithNaN, bool);
  vtkGetMacro(FillWithNaN, bool);
  vtkBooleanMacro(FillWithNaN, bool);
  vtkSetMacro(FillValue, double);
  vtkGetMacro(FillValue, double);
  ///@}

  ///@{
  /**
   * What the target points and cells the Source does not reach receive
   * instead of the fill value: NO_EXTRAPOLATION (default),
   * SMOOTH_EXTRAPOLATION (a creep fill over Input's point or cell graph,
   * each value a weighted mean of neighbours already reached: no new
   * extrema) or NEAREST_EXTRAPOLATION (the nearest valid value along the
   * graph). vtkExtrapolatedPointMask and vtkExtrapolatedCellMask mark
   * them; the valid values are those without extrapolation, bit for bit
   * (PreserveBounds is the switch that bounds them). GetMatrix
   * EXTRAPOLATION gives the extension.
   */
  enum Extrapolations
  {
    NO_EXTRAPOLATION = 0,
    SMOOTH_EXTRAPOLATION = 1,
    NEAREST_EXTRAPOLATION = 2
  };
  vtkSetClampMacro(Extrapolation, int, NO_EXTRAPOLATION, NEAREST_EXTRAPOLATION);
  vtkGetMacro(Extrapolation, int);
  ///@}

  ///@{
  /**
   * A well-posed fringe: point values whose support the Source covers less
   * than this fraction (default 0.25) take the least-squares extension of
   * well-covered points nearby instead of being fitted to a sliver; those
   * covered less than 10% (2% on linear surfaces and curves) become invalid; 0
   * turns it off.
   */
  vtkSetClampMacro(FringeThreshold, double, 0.0, 0.9);
  vtkGetMacro(FringeThreshold, double);
  ///@}

  ///@{
  /**
   * Which Source point and cell arrays are projected: all by default,
   * including arrays that appear later; disable them by name, e.g.
   * GetPointDataArraySelection()->DisableArray("p"). The filter lists
   * Source's arrays in them as it sees them (for ParaView's panel).
   */
  vtkDataArraySelection* GetPointDataArraySelection();
  vtkDataArraySelection* GetCellDataArraySelection();
  ///@}

  ///@{
  /**
   * ParaView's array lists (the PointDataArrays and CellDataArrays
   * properties): each change clears the selection, then states each named
   * array's status. A list naming every array the filter had listed (the
   * panel's) leaves arrays that appear later projected; a list naming fewer
   * projects only what it enables; a list naming none, all.
   */
  void ClearPointDataArrayStatuses();
  void SetPointDataArrayStatus(const char* name, int status);
  void ClearCellDataArrayStatuses();
  void SetCellDataArrayStatus(const char* name, int status);
  ///@}

  ///@{
  /**
   * TangentArrays: the names of 3-component Source point or cell arrays
   * that are vector fields tangent to a surface or curve (none by default).
   * Each is projected from its tangential part (its normal part at the
   * Source's points or cells removed) and returned in Input's tangent plane
   * (the normal part at each Input point or cell removed, with Input's own
   * normals; on a curve the part along its tangent is kept); the magnitude
   * removed at Input is written as "<name>_NormalPart". Other meshes
   * (volumes) project the array as an ordinary one, with a warning. See
   * docs/fields.md.
   */
  void AddTangentArray(const char* name);
  void ClearTangentArrays();
  int GetNumberOfTangentArrays() const;
  const char* GetTangentArray(int i) const;
  ///@}

  ///@{
  /**
   * Where Source point arrays go (default: TO_POINTS) and where Source cell
   * arrays go (default: TO_CELLS); TO_POINTS_AND_CELLS gives both.
   */
  vtkSetClampMacro(PointDataTarget, int, TO_POINTS, TO_POINTS_AND_CELLS);
  vtkGetMacro(PointDataTarget, int);
  vtkSetClampMacro(CellDataTarget, int, TO_POINTS, TO_POINTS_AND_CELLS);
  vtkGetMacro(CellDataTarget, int);
  ///@}

  ///@{
  /// INTENSIVE (default) or EXTENSIVE cell arrays. Point arrays are always intensive.
  vtkSetClampMacro(CellDataQuantity, int, INTENSIVE, EXTENSIVE);
  vtkGetMacro(CellDataQuantity, int);
  ///@}

  ///@{
  /**
   * How a Source cell array is seen on each Source cell before it is
   * projected: CONSTANT_RECONSTRUCTION (default), or a linear function with
   * the cell's mean and a gradient fitted to the neighbouring cells, limited
   * to the range of the cell and its neighbours (LIMITED_RECONSTRUCTION) or
   * not (UNLIMITED_RECONSTRUCTION, exact for linear fields). Integrals are
   * kept in every mode; extensive arrays are reconstructed as densities.
   */
  vtkSetClampMacro(CellDataReconstruction, int, CONSTANT_RECONSTRUCTION, UNLIMITED_RECONSTRUCTION);
  vtkGetMacro(CellDataReconstruction, int);
  ///@}

  ///@{
  /**
   * Mass-weighted projection. DensityArray names a one-component Source
   * array, the density rho (point data if Source has a point array of that
   * name, else cell data; default: none, off; "" or "None" turn it off). Each mass-weighted array q
   * of the same association is then projected so that the integral of
   * rho q is conserved: rho q and rho are projected (same operator, same
   * settings) and q's output is their ratio. Where the projected rho is at
   * most 1e-10 times the Source's largest |rho|, q gets the fill value and
   * is marked invalid in a mask of its own. With PreserveBounds, q is then
   * clipped to its Source range. The density itself is output only when it
   * is selected (GetPointDataArraySelection, ...). MassWeightedArrays: the
   * arrays to weight (default: none named, meaning every array of the
   * density's association); AddMassWeightedArray adds one name,
   * ClearMassWeightedArrays empties the list. SourceIntegral_<q> and
   * TargetIntegral_<q> are then the integrals of rho q. Cell data must be
   * INTENSIVE. Details: docs/fields.md.
   */
  void SetDensityArray(const char* name);
  const char* GetDensityArray() const { return this->DensityArray.c_str(); }
  void AddMassWeightedArray(const char* name);
  void ClearMassWeightedArrays();
  int GetNumberOfMassWeightedArrays() const;
  const char* GetMassWeightedArray(int i) const;
  ///@}

  ///@{
  /**
   * Categorical arrays (labels: material ids, regions, classes). A label
   * array is not averaged: each target cell takes the Source label that
   * covers most of its covered measure, each target point the label whose
   * Source cells (or points) weigh most under its basis function, both
   * read from the overlap matrix M_ts; ties go to the smallest label. The
   * output keeps the Source array's type. CategoricalMode says which
   * arrays are labels: CATEGORICAL_AUTOMATIC (default), every
   * single-component integer array (vtkIntArray, vtkIdTypeArray,
   * vtkUnsignedCharArray, ...; not vtkBitArray) with at most 1024 distinct
   * values (more: an id array, projected as numbers with a warning);
   * CATEGORICAL_SELECTED, exactly the
   * single-component point or cell arrays named with AddCategoricalArray
   * (so an integer array can be projected as numbers and a real array as
   * labels). Default: CATEGORICAL_AUTOMATIC, none named.
   */
  vtkSetClampMacro(CategoricalMode, int, CATEGORICAL_AUTOMATIC, CATEGORICAL_SELECTED);
  vtkGetMacro(CategoricalMode, int);
  void AddCategoricalArray(const char* name);
  void ClearCategoricalArrays();
  int GetNumberOfCategoricalArrays() const;
  const char* GetCategoricalArray(int i) const;
  ///@}

  ///@{
  /**
   * With LabelFractions, each label array also gives "<name>_Fractions":
   * per target point or cell, the weight of each label over the sum (one
   * component per label, named by it), which sum to 1; over the cells,
   * weighed by their covered measure, they sum to each label's Source
   * measure over the covered part. A label array with more than 256
   * labels gets none (a warning). Default: false.
   */
  vtkSetMacro(LabelFractions, bool);
  vtkGetMacro(LabelFractions, bool);
  vtkBooleanMacro(LabelFractions, bool);
  ///@}

  ///@{
  /**
   * The label of target points and cells the Source does not reach (an
   * unsigned array that cannot hold it gets its type's largest value).
   * Default: -1.
   */
  vtkSetMacro(FillLabel, int);
  vtkGetMacro(FillLabel, int);
  ///@}

  ///@{
  /// CONSISTENT_MASS (default): the L2 projection; LUMPED_MASS: bounded and cheap, first order.
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
   * go to the sparse direct solver. 0: the direct solver only. Default: 500.
   */
  vtkSetClampMacro(MaximumIterations, int, 0, 1000000);
  vtkGetMacro(MaximumIterations, int);
  ///@}

  ///@{
  /**
   * Surfaces in 3D. SurfaceReach: the largest distance between a source
   * facet and a target facet's plane at which they still meet, relative to
   * the target facet's longest edge (default 0.5, at most 100).
   * MaximumNormalAngle: the largest angle in degrees between the two
   * facets' normals (default 45, at most 89), so that the two sides of a
   * thin plate and the faces at a sharp edge are never matched. Both meshes
   * must be consistently oriented (vtkPolyDataNormals can fix others).
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
   * MaximumNormalAngle. SAME_ORIENTATION (default): as they are (two
   * facetizations of one surface). OPPOSITE_ORIENTATION: one reversed (two
   * bodies' boundaries facing each other: contact, fluid-structure
   * interaction). ANY_ORIENTATION: either way (orientation unknown; only
   * SurfaceReach then keeps a thin plate's two sides apart).
   */
  vtkSetClampMacro(NormalOrientation, int, SAME_ORIENTATION, ANY_ORIENTATION);
  vtkGetMacro(NormalOrientation, int);
  ///@}

  ///@{
  /**
   * Scales each projected array (each component, its valid values) so that
   * its integral over the covered target equals the Source field's integral
   * over the covered Source ("SourceIntegral_<name>"), for surfaces whose
   * two facetizations differ in area: loads and fluxes keep their totals.
   * A component whose two integrals differ by more than a factor of 2 is
   * left unscaled, with a warning. Linear fields are then no longer exact.
   * Default: false.
   */
  vtkSetMacro(ConserveSourceIntegral, bool);
  vtkGetMacro(ConserveSourceIntegral, bool);
  vtkBooleanMacro(ConserveSourceIntegral, bool);
  ///@}

  ///@{
  /**
   * Threads for the filter's parallel loops: 0 (default) uses every core,
   * in a local vtkSMPTools scope (on the STDThread backend when VTK's own is
   * the sequential one); 1, the calling thread only. Results depend on the
   * number of threads only through summation order.
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
   * (default): a mesh whose numbering does not follow space (shuffled, a
   * partitioner's order) is renumbered along a Morton curve, in a copy, so
   * that the time does not depend on the input's numbering; ALWAYS_RENUMBER
   * and NEVER_RENUMBER force either. The outputs are in the datasets' own
   * numbering in every case, equal up to summation order.
   */
  vtkSetClampMacro(Renumbering, int, AUTOMATIC_RENUMBERING, NEVER_RENUMBER);
  vtkGetMacro(Renumbering, int);
  ///@}

  ///@{
  /**
   * Curved second-order cells (mid nodes off their straight edges, as
   * meshers write them at curved boundaries) are met through a split into
   * simplices: at level L, the lattice of order 2 L of the reference cell
   * through the cell's isoparametric map, so that the split's boundary lies
   * within |d| / (4 L^2) of each curved edge (d: its mid node's offset from
   * the chord's middle) and the measures converge as 1 / L^2. 1: the
   * polygon or polyhedron through the nodes (|d| / 4), the default. Straight
   * cells are always split on their nodes. Applies to 3-node edges, 6-node
   * triangles, 8- and 9-node quadrilaterals and 10-node tetrahedra (and the
   * Lagrange cells of order 2 of those shapes); the other curved cells keep
   * the split on their nodes. A curved tetrahedron costs (2 L)^3 / 8 times
   * the simplices of L = 1.
   */
  vtkSetClampMacro(CurvedCellSubdivision, int, 1, 16);
  vtkGetMacro(CurvedCellSubdivision, int);
  ///@}

  ///@{
  /**
   * Keeps the operators between executions and reuses them while neither
   * mesh changes (time series on fixed meshes). Default: true. Off, nothing
   * is kept between executions and no matrices can be read out.
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
   * values. Rows are Input's points or cells, columns Input's (TARGET_MASS,
   * FRINGE_EXTENSION, EXTRAPOLATION) or Source's (MIXED_MASS), in VTK ids
   * (a composite Input: its first block; a composite Source: its blocks
   * one after the other). What each matrix holds, and how they give the
   * output: docs/user-guide.md, "The operator in your hands". GetMatrix reads
   * what the last execution kept and never executes the filter: it returns
   * the number of columns, or -1 (with an error) when the filter has not
   * executed, it or its inputs changed since (call Update() first), or
   * nothing was kept (CacheOperator off, KeepMatrices off on a one-off
   * execution, the transfer not in use). So: SetKeepMatrices(true),
   * Update(), GetMatrix(). On several processes it is not collective: each
   * process reads its own rows.
   */
  vtkIdType GetMatrix(int transfer, int matrix, vtkIdTypeArray* rowStart, vtkIdTypeArray* columns,
    vtkDoubleArray* values);
  /// Writes GetMatrix()'s matrix as a Matrix Market coordinate file (1-based); false on failure.
  bool WriteMatrixMarket(const char* fileName, int transfer, int matrix);

  ///@{
  /**
   * Results of the last execution (summed over the blocks of a composite
   * Input): intersecting simplex pairs, simplex-pair intersection tests,
   * locator queries, the covered area (2D) or volume (3D) of the target, and
   * the wall-clock seconds of the whole execution.
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
   * inputs (of which: CheckTime, checking both meshes' ids, offsets, types
   * and face streams; RenumberTime, renumbering them), the cell neighbours,
   * the locator, the pair search with the intersections and local
   * integrals, the assembly, the solve, and writing the outputs; and how
   * many of the two meshes (Source and the last leaf of Input) the last
   * execution renumbered.
   */
  vtkGetMacro(InputTime, double);
  vtkGetMacro(CheckTime, double);
  vtkGetMacro(RenumberTime, double);
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

  // The properties. Their defaults (stated above) are written once, in
  // Projection/Settings.h; the constructor sets them from there.
  int SearchMethod;
  bool OutputIntersections;
  bool FillWithNaN;
  double FillValue;
  int Extrapolation;
  double FringeThreshold;
  int PointDataTarget;
  int CellDataTarget;
  int CellDataQuantity;
  int CellDataReconstruction;
  int MassMatrix;
  bool PreserveBounds;
  int MaximumIterations;
  double SurfaceReach;
  double MaximumNormalAngle;
  int NormalOrientation;
  bool ConserveSourceIntegral;
  bool CacheOperator;
  bool KeepMatrices;
  int NumberOfThreads;
  int Renumbering;
  int CurvedCellSubdivision;
  std::string DensityArray;
  int CategoricalMode;
  bool LabelFractions;
  int FillLabel;

  // The results of the last execution.
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

  /// What the filter keeps between executions and the stages that take
  /// internal types (vtkMeshProjectionFilterInternals.h, private), where
  /// vtkPMeshProjectionFilter installs its processes.
  struct Internals;
  Internals* Internal;

private:
  vtkMeshProjectionFilter(const vtkMeshProjectionFilter&) = delete;
  void operator=(const vtkMeshProjectionFilter&) = delete;
  void SelectionModified();
  void ListSource(vtkDataObject* source);
};

#endif
