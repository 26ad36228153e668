// SPDX-License-Identifier: BSD-3-Clause
// Shared helpers of the VTK-level tests: reading the sample meshes, a
// triangulated unit square, exact integrals of P1 fields, a check macro that reports and counts
// failures, and one that runs a test's named case and reports it when it fails.
#ifndef MeshProjectionTestUtilities_h
#define MeshProjectionTestUtilities_h

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkDataSetMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
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
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #condition << std::endl;      \
      ++failures;                                                                                  \
    }                                                                                              \
  } while (false)

/// Runs one named case of a test: `call` returns true when every check in it passed; a failed
/// case is reported by name and counted in `failures` (the test's cases all run, in order).
#define MP_CASE(call)                                                                              \
  do                                                                                               \
  {                                                                                                \
    if (!(call))                                                                                   \
    {                                                                                              \
      std::cerr << "case failed: " #call << std::endl;                                             \
      ++failures;                                                                                  \
    }                                                                                              \
  } while (false)

namespace mptest
{
/// A ghost array (vtkGhostType) of n values, all 0 (nothing a ghost): the
/// caller marks its ghosts and adds it to the cell data.
inline vtkSmartPointer<vtkUnsignedCharArray> GhostArray(vtkIdType n)
{
  vtkNew<vtkUnsignedCharArray> ghosts;
  ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
  ghosts->SetNumberOfValues(n);
  ghosts->Fill(0);
  return ghosts;
}

inline vtkSmartPointer<vtkUnstructuredGrid> ReadSample(const std::string& name)
{
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((std::string(MESHPROJECTION_DATA_DIR) + "/" + name).c_str());
  reader->Update();
  vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
  return grid;
}

/// [0, 1]^2 in nx x ny squares, two triangles each (or one quad each), with
/// point arrays Linear = 1 + 2x - 3y and Other = 1 + x, cell array Density
/// = 2 + cell index % 3.
inline vtkSmartPointer<vtkUnstructuredGrid> Square(int nx, int ny, bool quads = false)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> linear;
  linear->SetName("Linear");
  vtkNew<vtkDoubleArray> other;
  other->SetName("Other");
  for (int j = 0; j <= ny; ++j)
  {
    for (int i = 0; i <= nx; ++i)
    {
      const double x = double(i) / nx;
      const double y = double(j) / ny;
      points->InsertNextPoint(x, y, 0.0);
      linear->InsertNextValue(1 + 2 * x - 3 * y);
      other->InsertNextValue(1 + x);
    }
  }
  grid->SetPoints(points);
  grid->Allocate(2 * nx * ny);
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const vtkIdType a = j * (nx + 1) + i;
      const vtkIdType q[4] = { a, a + 1, a + nx + 2, a + nx + 1 };
      if (quads)
      {
        grid->InsertNextCell(VTK_QUAD, 4, q);
        continue;
      }
      const vtkIdType t1[3] = { q[0], q[1], q[2] };
      const vtkIdType t2[3] = { q[0], q[2], q[3] };
      grid->InsertNextCell(VTK_TRIANGLE, 3, t1);
      grid->InsertNextCell(VTK_TRIANGLE, 3, t2);
    }
  }
  grid->GetPointData()->AddArray(linear);
  grid->GetPointData()->AddArray(other);
  vtkNew<vtkDoubleArray> density;
  density->SetName("Density");
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    density->InsertNextValue(2 + c % 3);
  }
  grid->GetCellData()->AddArray(density);
  return grid;
}

/// One hexahedron and one polyhedron (the unit cube twice, side by side).

/// Area of a triangle or volume of a tetrahedron (cell c); its point ids in `ids`.
inline double CellMeasure(
  vtkUnstructuredGrid* grid, vtkIdType c, const vtkIdType** ids, vtkIdType* n)
{
  grid->GetCells()->GetCellAtId(c, *n, *ids);
  double x[4][3];
  for (vtkIdType k = 0; k < *n && k < 4; ++k)
  {
    grid->GetPoint((*ids)[k], x[k]);
  }
  double e[3][3];
  for (int k = 0; k < 3; ++k)
  {
    for (int d = 0; d < 3; ++d)
    {
      e[k][d] = x[k + 1][d] - x[0][d];
    }
  }
  if (*n == 3)
  {
    return 0.5 * std::fabs(e[0][0] * e[1][1] - e[0][1] * e[1][0]);
  }
  return std::fabs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
           e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
           e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
    6.0;
}

/// Exact integral of component `k` of a P1 point array over a simplicial mesh.
inline double Integral(vtkUnstructuredGrid* grid, vtkDataArray* u, int k = 0)
{
  double sum = 0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const vtkIdType* ids;
    vtkIdType n;
    const double measure = CellMeasure(grid, c, &ids, &n);
    double mean = 0;
    for (vtkIdType j = 0; j < n; ++j)
    {
      mean += u->GetComponent(ids[j], k) / n;
    }
    sum += measure * mean;
  }
  return sum;
}

/// Total area (triangles) or volume (tetrahedra).
inline double Measure(vtkUnstructuredGrid* grid)
{
  double sum = 0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const vtkIdType* ids;
    vtkIdType n;
    sum += CellMeasure(grid, c, &ids, &n);
  }
  return sum;
}
/**
 * The image half of a test: `left` and `right` side by side in a 600 x 300
 * window, coloured by point array `array` over the range it has on `left`,
 * with cell edges, compared with the test's baseline. Returns the
 * vtkRegressionTester result.
 */
inline int SideBySideImageTest(
  int argc, char* argv[], vtkDataSet* left, vtkDataSet* right, const char* array)
{
  double range[2];
  left->GetPointData()->GetArray(array)->GetRange(range);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(600, 300);
  window->SetMultiSamples(0);
  vtkDataSet* shown[2] = { left, right };
  for (int side = 0; side < 2; ++side)
  {
    vtkNew<vtkDataSetMapper> mapper;
    mapper->SetInputData(shown[side]);
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray(array);
    mapper->SetScalarRange(range);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->EdgeVisibilityOn();
    actor->GetProperty()->SetEdgeColor(0.15, 0.15, 0.15);
    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(0.5 * side, 0, 0.5 * side + 0.5, 1);
    renderer->SetBackground(1, 1, 1);
    renderer->AddActor(actor);
    renderer->ResetCamera();
    renderer->GetActiveCamera()->Zoom(1.3);
    window->AddRenderer(renderer);
  }
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  window->Render();
  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  return result;
}
} // namespace mptest

#endif
