// SPDX-License-Identifier: BSD-3-Clause
#include "Adapter/FieldArrays.h"

#include "vtkAbstractArray.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"

namespace mpvtk
{
vtkDataSetAttributes* AttributesOf(vtkDataSet* data, int association)
{
  return data->GetAttributes(association == 0 ? vtkDataObject::POINT : vtkDataObject::CELL);
}

bool IsMask(const std::string& name)
{
  return name.rfind("vtkValidPointMask", 0) == 0 || name.rfind("vtkValidCellMask", 0) == 0 ||
    name.rfind("vtkExtrapolatedPointMask", 0) == 0 || name.rfind("vtkExtrapolatedCellMask", 0) == 0;
}

namespace
{
/// Ids of a dataset's own points or cells (its GlobalIds and PedigreeIds, and
/// the vtkOriginalPointIds/CellIds that extraction and redistribution
/// filters add).
bool IsIdArray(vtkDataSetAttributes* data, vtkAbstractArray* array)
{
  const char* name = array->GetName();
  return array == data->GetGlobalIds() || array == data->GetPedigreeIds() ||
    (name &&
      (std::string(name) == "vtkOriginalPointIds" || std::string(name) == "vtkOriginalCellIds"));
}
} // namespace

bool IsField(vtkDataSetAttributes* data, vtkAbstractArray* array)
{
  if (!array)
  {
    return false;
  }
  const char* name = array->GetName();
  if (name && (std::string(name) == vtkDataSetAttributes::GhostArrayName() || IsMask(name)))
  {
    return false;
  }
  return !IsIdArray(data, array);
}
} // namespace mpvtk
