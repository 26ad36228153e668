// SPDX-License-Identifier: BSD-3-Clause
#include "Adapter/CompositeLeaves.h"

#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSet.h"
#include "vtkInformation.h"
#include "vtkSmartPointer.h"

namespace mpvtk
{
void ForEachLeaf(
  vtkDataObject* data, const std::function<void(vtkCompositeDataIterator* at)>& visit)
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

std::string BlockName(unsigned int flat, const char* name)
{
  return name ? std::string("block '") + name + "' (flat index " + std::to_string(flat) + ")"
              : "block of flat index " + std::to_string(flat);
}

std::string BlockName(vtkCompositeDataIterator* at)
{
  const char* name =
    at->HasCurrentMetaData() ? at->GetCurrentMetaData()->Get(vtkCompositeDataSet::NAME()) : nullptr;
  return BlockName(at->GetCurrentFlatIndex(), name);
}
} // namespace mpvtk
