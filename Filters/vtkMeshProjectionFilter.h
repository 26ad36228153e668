// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMeshProjectionFilter
 * @brief   Transfers point data between two non-matching meshes by mortar L2 projection.
 *
 * vtkMeshProjectionFilter fills the points of a target mesh (input port 0,
 * "Input") with the point data of a source mesh (input port 1, "Source")
 * such that the projected field is the L2-best P1 approximation of the
 * source field on the target: it solves M_tt u_t = M_ts u_s, where M_tt is
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
 * 2009): neighbours come from VTK's static cell links; a front starts with
 * a walk through the source, and re-seeds from a vtkStaticCellLocator over
 * the source's boundary cells (one over all source cells is built only when
 * that cannot settle a cell, e.g. targets reaching beyond the source); the
 * geometry and the numerics live in a VTK-free kernel (Filters/Kernel).
 *
 * Inputs: two vtkUnstructuredGrid of the same dimension: linear triangles
 * (VTK_TRIANGLE) lying in one plane, any plane (2D meshes with 3D
 * coordinates), or linear tetrahedra (VTK_TETRA). They need not cover the
 * same region, be connected or convex.
 *
 * Output port 0: a shallow copy of Input with, for every numeric point array
 * of Source (any type, any number of components), a vtkDoubleArray of the
 * same name and components holding the projected field (an Input array of
 * the same name is replaced); plus
 *  - "vtkValidPointMask" (char point array): 1 where the point's support
 *    meets the source, else 0; invalid points get NaN (or FillValue);
 *  - "CoveredFraction" (double cell array): the fraction of each target
 *    cell's area (volume) covered by the source.
 * When OutputIntersections is on:
 *  - output port 1 (2D inputs): the intersection polygons, vtkPolyData with
 *    cell arrays "SourceCellId", "TargetCellId" (vtkIdType) and "Area";
 *  - output port 2 (3D inputs): the intersection polyhedra as their
 *    tetrahedral decomposition, vtkUnstructuredGrid with cell arrays
 *    "SourceCellId", "TargetCellId" and "Volume" (of each tetrahedron).
 * The port not used by the inputs' dimension stays empty.
 *
 * Non-numeric Source point arrays (strings, variants) are skipped with a
 * warning; integer arrays are projected as real values, with a warning (an
 * L2 projection of labels or ids is not meaningful). Invalid input (no
 * Source, other cell types, a mix of triangles and tetrahedra, meshes of
 * different dimensions, non-planar triangle meshes, NaN/Inf coordinates)
 * produces an error and an output that is a plain copy of Input; empty
 * meshes and meshes that do not overlap give a warning and invalid points.
 *
 * Threads: the search, the intersections and the local integrals run in one
 * task per vtkSMPTools thread (ranges of target cells, each with its own
 * advancing front); results equal the serial ones up to summation order.
 * @warning Debian's VTK 9.2 uses the sequential SMP backend by default: set
 * VTK_SMP_BACKEND_IN_USE=STDThread (or call vtkSMPTools::SetBackend) to run
 * on several threads.
 *
 * @sa vtkResampleWithDataSet vtkProbeFilter
 */
#ifndef vtkMeshProjectionFilter_h
#define vtkMeshProjectionFilter_h

#include "MeshProjectionFiltersModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

class MESHPROJECTIONFILTERS_EXPORT vtkMeshProjectionFilter : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkMeshProjectionFilter* New();
  vtkTypeMacro(vtkMeshProjectionFilter, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum SearchMethods
  {
    ADVANCING_FRONT = 0, ///< Gander & Japhet's front over neighbours: linear complexity
    BRUTE_FORCE = 1      ///< every target cell against every source cell: O(n m), for checks
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
   * Results of the last execution: intersecting cell pairs with an
   * intersection of positive measure, cell-pair intersection tests, locator
   * queries (among the source's boundary cells or all its cells), the
   * covered area (2D) or volume (3D) of the target, and the wall-clock
   * seconds of the whole execution.
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
   * inputs (cell types, coordinate checks, the fields gathered), the cell
   * neighbours (VTK cell links), the locator over the source's boundary
   * cells (vtkStaticCellLocator), the pair search with the intersections and
   * local integrals (and a locator over all source cells, when one is
   * needed), the assembly, the solve, and writing the outputs.
   */
  vtkGetMacro(InputTime, double);
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
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int SearchMethod = ADVANCING_FRONT;
  bool OutputIntersections = false;
  bool FillWithNaN = true;
  double FillValue = 0;

  vtkIdType NumberOfIntersections = 0;
  vtkIdType NumberOfIntersectionTests = 0;
  vtkIdType NumberOfLocatorQueries = 0;
  double CoveredMeasure = 0;
  double ExecutionTime = 0;
  double InputTime = 0;
  double NeighborsTime = 0;
  double LocatorTime = 0;
  double SearchTime = 0;
  double AssemblyTime = 0;
  double SolveTime = 0;
  double OutputTime = 0;

private:
  vtkMeshProjectionFilter(const vtkMeshProjectionFilter&) = delete;
  void operator=(const vtkMeshProjectionFilter&) = delete;
};

#endif
