// SPDX-License-Identifier: BSD-3-Clause
#include "Parallel/CellCopier.h"

#include "vtkCellArray.h"
#include "vtkIdTypeArray.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>

namespace mpvtk
{
void CellCopier::Finish() const
{
  if (this->Polyhedra)
  {
    return;
  }
  auto array = [](const std::vector<vtkIdType>& values) {
    vtkNew<vtkIdTypeArray> a;
    a->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
    std::copy(values.begin(), values.end(), a->GetPointer(0));
    return a;
  };
  vtkNew<vtkCellArray> cells;
  cells->SetData(array(this->Offsets), array(this->Connectivity));
  vtkNew<vtkUnsignedCharArray> types;
  types->SetNumberOfValues(static_cast<vtkIdType>(this->Types.size()));
  std::copy(this->Types.begin(), this->Types.end(), types->GetPointer(0));
  this->To->SetCells(types, cells);
}
} // namespace mpvtk
