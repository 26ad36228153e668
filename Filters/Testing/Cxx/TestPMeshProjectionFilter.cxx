// SPDX-License-Identifier: BSD-3-Clause
// A plain VTK C++ program with vtkMPIController (run under mpiexec): each
// process reads the sample meshes, keeps its own cells of Input (every
// size-th cell) and of Source (a contiguous block), and projects with
// vtkPMeshProjectionFilter. Its points' values must equal the serial
// filter's on the whole meshes (1e-10 of the range), the valid masks too,
// and the integrals (totals over the processes) the serial ones.
#include "vtkPMeshProjectionFilter.h"

#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExtractCells.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkMPIController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridReader.h"

#include <cmath>
#include <iostream>
#include <string>

namespace
{
vtkSmartPointer<vtkUnstructuredGrid> Read(const std::string& name)
{
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((std::string(MESHPROJECTION_DATA_DIR) + "/" + name).c_str());
  reader->Update();
  vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("origId");
  for (vtkIdType p = 0; p < grid->GetNumberOfPoints(); ++p)
  {
    ids->InsertNextValue(p);
  }
  grid->GetPointData()->AddArray(ids);
  return grid;
}

vtkSmartPointer<vtkUnstructuredGrid> Part(
  vtkUnstructuredGrid* grid, int rank, int size, bool strided)
{
  vtkNew<vtkIdList> keep;
  const vtkIdType n = grid->GetNumberOfCells();
  for (vtkIdType c = 0; c < n; ++c)
  {
    const int owner = strided ? static_cast<int>(c % size) : static_cast<int>(c * size / n);
    if (owner == rank)
    {
      keep->InsertNextId(c);
    }
  }
  vtkNew<vtkExtractCells> extract;
  extract->SetInputData(grid);
  extract->SetCellList(keep);
  extract->Update();
  vtkSmartPointer<vtkUnstructuredGrid> part = extract->GetOutput();
  return part;
}

int Compare(const char* what, const std::string& target, const std::string& source, int rank,
  int size, vtkMultiProcessController* controller)
{
  int failures = 0;
  vtkSmartPointer<vtkUnstructuredGrid> t = Read(target);
  vtkSmartPointer<vtkUnstructuredGrid> s = Read(source);
  s->GetPointData()->RemoveArray("origId");
  vtkNew<vtkMeshProjectionFilter> serial;
  serial->SetInputData(t);
  serial->SetSourceData(s);
  serial->Update();
  vtkDataSet* whole = vtkDataSet::SafeDownCast(serial->GetOutputDataObject(0));

  vtkNew<vtkPMeshProjectionFilter> parallel;
  parallel->SetController(controller);
  parallel->SetInputData(Part(t, rank, size, true));
  parallel->SetSourceData(Part(s, rank, size, false));
  parallel->Update();
  vtkDataSet* mine = vtkDataSet::SafeDownCast(parallel->GetOutputDataObject(0));

  vtkIdTypeArray* ids = vtkIdTypeArray::SafeDownCast(mine->GetPointData()->GetArray("origId"));
  vtkDataArray* mask = mine->GetPointData()->GetArray("vtkValidPointMask");
  vtkDataArray* wholeMask = whole->GetPointData()->GetArray("vtkValidPointMask");
  if (!ids || !mask || !wholeMask)
  {
    std::cerr << what << ": arrays missing on process " << rank << std::endl;
    return 1;
  }
  int compared = 0;
  for (int a = 0; a < s->GetPointData()->GetNumberOfArrays(); ++a)
  {
    const char* name = s->GetPointData()->GetArrayName(a);
    vtkDataArray* u = mine->GetPointData()->GetArray(name);
    vtkDataArray* w = whole->GetPointData()->GetArray(name);
    if (!u || !w)
    {
      std::cerr << what << ": " << name << " missing on process " << rank << std::endl;
      ++failures;
      continue;
    }
    double range[2];
    s->GetPointData()->GetArray(name)->GetRange(range, -1);
    const double scale = range[1] > range[0] ? range[1] - range[0] : 1.0;
    double worst = 0;
    for (vtkIdType p = 0; p < mine->GetNumberOfPoints(); ++p)
    {
      const vtkIdType o = ids->GetValue(p);
      if (mask->GetTuple1(p) != wholeMask->GetTuple1(o))
      {
        ++failures;
        continue;
      }
      if (mask->GetTuple1(p) == 0)
      {
        continue;
      }
      for (int k = 0; k < u->GetNumberOfComponents(); ++k)
      {
        worst = std::max(worst, std::fabs(u->GetComponent(p, k) - w->GetComponent(o, k)) / scale);
      }
    }
    ++compared;
    if (!(worst <= 1e-10))
    {
      std::cerr << what << ": " << name << " differs from serial by " << worst
                << " of its range on process " << rank << std::endl;
      ++failures;
    }
    for (const char* prefix : { "SourceIntegral_", "TargetIntegral_" })
    {
      const std::string field = std::string(prefix) + name;
      vtkDataArray* pi = mine->GetFieldData()->GetArray(field.c_str());
      vtkDataArray* si = whole->GetFieldData()->GetArray(field.c_str());
      if (!pi || !si ||
        !(std::fabs(pi->GetComponent(0, 0) - si->GetComponent(0, 0)) <=
          1e-10 * std::fabs(si->GetComponent(0, 0))))
      {
        std::cerr << what << ": " << field << " is not the serial total on process " << rank
                  << std::endl;
        ++failures;
      }
    }
  }
  if (compared == 0)
  {
    ++failures;
  }
  return failures;
}
} // namespace

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  vtkMultiProcessController::SetGlobalController(controller);
  const int rank = controller->GetLocalProcessId();
  const int size = controller->GetNumberOfProcesses();
  int failures = 0;
  failures += Compare("2D", "lshape_target.vtu", "lshape_source.vtu", rank, size, controller);
  failures += Compare("3D", "lshape3d_target.vtu", "lshape3d_source.vtu", rank, size, controller);
  int total = 0;
  controller->AllReduce(&failures, &total, 1, vtkCommunicator::SUM_OP);
  if (rank == 0)
  {
    std::cout << size << " processes: " << (total ? "FAILED" : "serial result reproduced")
              << std::endl;
  }
  controller->Finalize();
  return total ? 1 : 0;
}
