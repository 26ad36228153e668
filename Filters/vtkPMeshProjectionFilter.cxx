// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPMeshProjectionFilter.h"

#include "vtkMeshProjectionFilterInternals.h"

#include "Parallel/MPIParts.h"
#include "Projection/Outputs.h"

#include "vtkCommunicator.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMPICommunicator.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnstructuredGrid.h"

vtkStandardNewMacro(vtkPMeshProjectionFilter);
vtkCxxSetObjectMacro(vtkPMeshProjectionFilter, Controller, vtkMultiProcessController);

//------------------------------------------------------------------------------
vtkPMeshProjectionFilter::vtkPMeshProjectionFilter()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPMeshProjectionFilter::~vtkPMeshProjectionFilter()
{
  this->SetController(nullptr);
}

int vtkPMeshProjectionFilter::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestUpdateExtent(request, inputVector, outputVector))
  {
    return 0;
  }
  if (this->Controller && this->Controller->GetNumberOfProcesses() > 1)
  {
    // Each process reads its own piece of Source (not the whole of it): the
    // cells its part of Input needs come from the others.
    using SDDP = vtkStreamingDemandDrivenPipeline;
    vtkInformation* outInfo = outputVector->GetInformationObject(0);
    vtkInformation* sourceInfo = inputVector[1]->GetInformationObject(0);
    if (sourceInfo)
    {
      sourceInfo->CopyEntry(outInfo, SDDP::UPDATE_PIECE_NUMBER());
      sourceInfo->CopyEntry(outInfo, SDDP::UPDATE_NUMBER_OF_PIECES());
      sourceInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    }
  }
  return 1;
}

int vtkPMeshProjectionFilter::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->GlobalNumberOfIntersections = 0;
  this->GlobalCoveredMeasure = 0;
  this->GlobalReceivedSourceCells = this->ReceivedSourceCells = 0;
  this->GlobalSentBytes = this->SentBytes = 0;
  vtkMultiProcessController* controller = this->Controller;
  if (!controller || controller->GetNumberOfProcesses() <= 1)
  {
    const int done = this->Superclass::RequestData(request, inputVector, outputVector);
    this->GlobalNumberOfIntersections = this->NumberOfIntersections;
    this->GlobalCoveredMeasure = this->CoveredMeasure;
    return done;
  }
  if (!vtkMPICommunicator::SafeDownCast(controller->GetCommunicator()))
  {
    vtkErrorMacro(<< "Several processes need an MPI controller (vtkMPIController); this one is a "
                  << controller->GetClassName() << ".");
    return 0;
  }
  mpvtk::MPIParts parts(controller);
  // Whether there is anything to project is agreed before any collective:
  // a process without Input or Source ends every process with its error
  // (the serial filter decides it per process, where a process that stops
  // would leave the others waiting in the gathering).
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  const mpvtk::Verdict present = parts.Agree(!input
      ? mpvtk::Verdict::Fail("No Input on this process (input port 0): nothing to project.")
      : !vtkDataObject::GetData(inputVector[1], 0)
      ? mpvtk::Verdict::Fail("No Source is connected (input port 1): nothing to project.")
      : mpvtk::Verdict());
  if (!present.Ok())
  {
    if (input)
    {
      mpvtk::PassInput(input, vtkDataObject::GetData(outputVector, 0),
        vtkPolyData::GetData(outputVector, 1), vtkUnstructuredGrid::GetData(outputVector, 2));
    }
    vtkErrorMacro(<< present.Message());
    return 1;
  }
  this->Internal->Parts = &parts;
  const int done = this->Superclass::RequestData(request, inputVector, outputVector);
  this->Internal->Parts = nullptr;
  this->ReceivedSourceCells = parts.Received;
  this->SentBytes = parts.SentBytes();
  double totals[4] = { static_cast<double>(this->NumberOfIntersections), this->CoveredMeasure,
    static_cast<double>(this->ReceivedSourceCells), this->SentBytes };
  double sums[4] = { 0, 0, 0, 0 };
  controller->AllReduce(totals, sums, 4, vtkCommunicator::SUM_OP);
  this->GlobalNumberOfIntersections = static_cast<vtkIdType>(sums[0]);
  this->GlobalCoveredMeasure = sums[1];
  this->GlobalReceivedSourceCells = static_cast<vtkIdType>(sums[2]);
  this->GlobalSentBytes = sums[3];
  return done;
}

void vtkPMeshProjectionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "GlobalNumberOfIntersections: " << this->GlobalNumberOfIntersections << "\n";
  os << indent << "GlobalCoveredMeasure: " << this->GlobalCoveredMeasure << "\n";
  os << indent << "GlobalReceivedSourceCells: " << this->GlobalReceivedSourceCells << "\n";
  os << indent << "GlobalSentBytes: " << this->GlobalSentBytes << "\n";
}
