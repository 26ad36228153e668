// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPMeshProjectionFilter
 * @brief   vtkMeshProjectionFilter on several MPI processes: the same
 *          projection, whatever the partitioning.
 *
 * Each process projects onto its own part of Input. It receives, from every
 * process, the Source cells that can meet that part (an exchange by
 * bounding boxes: no process needs the whole Source unless it is stored
 * whole on one), and builds the local operator with the serial machinery.
 * The mass matrix is one global system: the points a process shares with
 * others (found by the GlobalIds point array when every process has one,
 * else by their coordinates) have their rows summed across the processes,
 * and the conjugate gradients run over all of them. The result equals the
 * serial one up to summation order (the tests compare to 1e-10): cells
 * other than simplices are split from their corner of lowest GlobalIds
 * value where the dataset has them, else of lowest point id in the
 * process's piece (a Source piece's ids as its process numbers them),
 * which is the serial split when the GlobalIds follow the serial
 * numbering, or the pieces keep the serial order of their points (as
 * extracting cells does); else the split may differ, by O(h^2) for smooth
 * fields, from a serial run's.
 *
 * A failure on any process (a corrupt piece, no Input or Source on one
 * process, a failed solve, an exception in a step of one process) is the
 * same error on every process, naming that process, and every output is
 * Input as it came; an exception inside a step the processes run
 * together aborts the MPI run (docs/mpi.md).
 *
 * Ghost cells of either input are left out, as in serial runs; the points
 * of Input's ghost cells get the values their owners compute. Per process:
 * the output arrays, the masks and covered fractions, the intersection
 * outputs, and the superclass's statistics; the field data integrals
 * (SourceIntegral_, TargetIntegral_) and the Global... statistics here are
 * totals over the processes. PreserveBounds too gives the serial result
 * (each point's bounds completed across the processes that share it).
 *
 * With one process (or no controller) it is the serial filter, as
 * vtkPResampleWithDataSet is vtkResampleWithDataSet's. The controller is the
 * global one by default; several processes need an MPI controller.
 *
 * @sa vtkMeshProjectionFilter vtkPResampleWithDataSet vtkMPIController
 */
#ifndef vtkPMeshProjectionFilter_h
#define vtkPMeshProjectionFilter_h

#include "MeshProjectionFiltersModule.h" // for export macro
#include "vtkMeshProjectionFilter.h"

class vtkMultiProcessController;

class MESHPROJECTIONFILTERS_EXPORT vtkPMeshProjectionFilter : public vtkMeshProjectionFilter
{
public:
  static vtkPMeshProjectionFilter* New();
  vtkTypeMacro(vtkPMeshProjectionFilter, vtkMeshProjectionFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The processes (default: the global controller).
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /**
   * Totals over the processes of the last execution: intersection pieces,
   * covered measure, Source cells received (copies of one cell on several
   * processes counted each time), and bytes sent (Source cells and shared
   * rows). ReceivedSourceCells and SentBytes: this process's share.
   */
  vtkGetMacro(GlobalNumberOfIntersections, vtkIdType);
  vtkGetMacro(GlobalCoveredMeasure, double);
  vtkGetMacro(GlobalReceivedSourceCells, vtkIdType);
  vtkGetMacro(GlobalSentBytes, double);
  vtkGetMacro(ReceivedSourceCells, vtkIdType);
  vtkGetMacro(SentBytes, double);
  ///@}

protected:
  vtkPMeshProjectionFilter();
  ~vtkPMeshProjectionFilter() override;

  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkMultiProcessController* Controller = nullptr;
  vtkIdType GlobalNumberOfIntersections = 0;
  double GlobalCoveredMeasure = 0;
  vtkIdType GlobalReceivedSourceCells = 0;
  double GlobalSentBytes = 0;
  vtkIdType ReceivedSourceCells = 0;
  double SentBytes = 0;

private:
  vtkPMeshProjectionFilter(const vtkPMeshProjectionFilter&) = delete;
  void operator=(const vtkPMeshProjectionFilter&) = delete;
};

#endif
