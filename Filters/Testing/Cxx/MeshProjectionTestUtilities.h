// SPDX-License-Identifier: BSD-3-Clause
// Shared helpers of the VTK-level tests: reading the sample meshes, exact
// integrals of P1 fields, and a check macro that reports and counts failures.
#ifndef MeshProjectionTestUtilities_h
#define MeshProjectionTestUtilities_h

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridReader.h"

#include <cmath>
#include <iostream>
#include <string>

#define MP_CHECK(condition)                                                                        \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #condition << std::endl;     \
      ++failures;                                                                                  \
    }                                                                                              \
  } while (false)

namespace mptest
{
inline vtkSmartPointer<vtkUnstructuredGrid> ReadSample(const std::string& name)
{
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((std::string(MESHPROJECTION_DATA_DIR) + "/" + name).c_str());
  reader->Update();
  vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
  return grid;
}

inline double TriangleArea(vtkUnstructuredGrid* grid, vtkIdType c, const vtkIdType** ids)
{
  vtkIdType n;
  grid->GetCells()->GetCellAtId(c, n, *ids);
  double a[3];
  double b[3];
  double d[3];
  grid->GetPoint((*ids)[0], a);
  grid->GetPoint((*ids)[1], b);
  grid->GetPoint((*ids)[2], d);
  return 0.5 * std::fabs((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]));
}

/// Exact integral of component `k` of a P1 point array over a triangle mesh.
inline double Integral(vtkUnstructuredGrid* grid, vtkDataArray* u, int k = 0)
{
  double sum = 0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const vtkIdType* ids;
    const double area = TriangleArea(grid, c, &ids);
    sum += area *
      (u->GetComponent(ids[0], k) + u->GetComponent(ids[1], k) + u->GetComponent(ids[2], k)) / 3;
  }
  return sum;
}

inline double Area(vtkUnstructuredGrid* grid)
{
  double sum = 0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const vtkIdType* ids;
    sum += TriangleArea(grid, c, &ids);
  }
  return sum;
}
} // namespace mptest

#endif
