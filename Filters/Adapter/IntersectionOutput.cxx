// SPDX-License-Identifier: BSD-3-Clause
#include "Adapter/IntersectionOutput.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <functional>

namespace mpvtk
{
namespace
{
/// The pieces' points and cells, with SourceCellId / TargetCellId (VTK ids)
/// and the measure of each cell.
template <class DataSet>
vtkSmartPointer<DataSet> MakePieces(const mp::IntersectionPieces& pieces, const SimplexMesh& target,
  const SimplexMesh& source, const char* measureName,
  const std::function<void(DataSet*, vtkCellArray*)>& setCells)
{
  auto result = vtkSmartPointer<DataSet>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const vtkIdType nv = static_cast<vtkIdType>(pieces.Points.size() / 3);
  points->SetNumberOfPoints(nv);
  for (vtkIdType v = 0; v < nv; ++v)
  {
    double x[3];
    if (target.View().SpaceDimension == 2 && pieces.Dimension < 3)
    {
      // Back into the target's plane (a planar mesh, or a curve in a planar Source).
      target.Frame().ToSpace(&pieces.Points[3 * v], x);
    }
    else
    {
      std::copy_n(&pieces.Points[3 * v], 3, x);
    }
    points->SetPoint(v, x);
  }
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(pieces.Offsets.size()));
  std::copy(pieces.Offsets.begin(), pieces.Offsets.end(), offsets->GetPointer(0));
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(nv);
  for (vtkIdType v = 0; v < nv; ++v)
  {
    connectivity->SetValue(v, v);
  }
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  result->SetPoints(points);
  setCells(result, cells);

  auto idArray = [&](const char* name, const std::vector<mp::Index>& values,
                   const SimplexMesh& mesh) {
    vtkNew<vtkIdTypeArray> a;
    a->SetName(name);
    a->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
    for (size_t i = 0; i < values.size(); ++i)
    {
      a->SetValue(static_cast<vtkIdType>(i), mesh.View().ParentOf(values[i]));
    }
    result->GetCellData()->AddArray(a);
  };
  idArray("SourceCellId", pieces.SourceCell, source);
  idArray("TargetCellId", pieces.TargetCell, target);
  vtkNew<vtkDoubleArray> measure;
  measure->SetName(measureName);
  measure->SetNumberOfValues(static_cast<vtkIdType>(pieces.Measure.size()));
  std::copy(pieces.Measure.begin(), pieces.Measure.end(), measure->GetPointer(0));
  result->GetCellData()->AddArray(measure);
  return result;
}
} // namespace

vtkSmartPointer<vtkPolyData> MakeIntersectionPolygons(
  const mp::IntersectionPieces& pieces, const SimplexMesh& target, const SimplexMesh& source)
{
  return MakePieces<vtkPolyData>(pieces, target, source, "Area",
    [](vtkPolyData* p, vtkCellArray* cells) { p->SetPolys(cells); });
}

vtkSmartPointer<vtkPolyData> MakeIntersectionSegments(
  const mp::IntersectionPieces& pieces, const SimplexMesh& target, const SimplexMesh& source)
{
  return MakePieces<vtkPolyData>(pieces, target, source, "Length",
    [](vtkPolyData* p, vtkCellArray* cells) { p->SetLines(cells); });
}

vtkSmartPointer<vtkUnstructuredGrid> MakeIntersectionPolyhedra(
  const mp::IntersectionPieces& pieces, const SimplexMesh& target, const SimplexMesh& source)
{
  return MakePieces<vtkUnstructuredGrid>(pieces, target, source, "Volume",
    [](vtkUnstructuredGrid* g, vtkCellArray* cells) { g->SetCells(VTK_TETRA, cells); });
}
} // namespace mpvtk
