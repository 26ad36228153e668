// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Composite.h"

#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSet.h"
#include "vtkInformation.h"
#include "vtkSmartPointer.h"

namespace mpvtk
{
void ForEachLeaf(vtkDataObject* data, const std::function<void(vtkCompositeDataIterator* at)>& visit)
{
  vtkCompositeDataSet* composite = vtkCompositeDataSet::SafeDownCast(data);
  if (!composite)
  {
    return;
  }
  vtkSmartPointer<vtkCompositeDataIterator> iter;
  iter.TakeReference(composite->NewIterator());
  iter->SkipEmptyNodesOn();
  for (iter->InitTraversal(); !iter->IsDoneWithTraversal(); iter->GoToNextItem())
  {
    visit(iter);
  }
}

std::vector<vtkDataSet*> DataSetsOf(vtkDataObject* data)
{
  std::vector<vtkDataSet*> all;
  if (vtkDataSet* one = vtkDataSet::SafeDownCast(data))
  {
    all.push_back(one);
  }
  ForEachLeaf(data, [&](vtkCompositeDataIterator* at) {
    if (vtkDataSet* leaf = vtkDataSet::SafeDownCast(at->GetCurrentDataObject()))
    {
      all.push_back(leaf);
    }
  });
  return all;
}

std::string BlockName(vtkCompositeDataIterator* at)
{
  const unsigned int flat = at->GetCurrentFlatIndex();
  const char* name =
    at->HasCurrentMetaData() ? at->GetCurrentMetaData()->Get(vtkCompositeDataSet::NAME()) : nullptr;
  return name ? std::string("block '") + name + "' (flat index " + std::to_string(flat) + ")"
              : "block of flat index " + std::to_string(flat);
}
} // namespace mpvtk
