// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/ArraySelection.h"

#include "vtkAbstractArray.h"
#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkDataArraySelection.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"

#include "Adapter/CompositeLeaves.h"
#include "Adapter/FieldArrays.h"

#include <algorithm>
#include "vtkDataSetAttributes.h"

namespace mpvtk
{
SourceArrayLists::SourceArrayLists()
{
  for (vtkDataArraySelection* selection : this->Selections)
  {
    selection->SetUnknownArraySetting(1);
  }
}

vtkDataArraySelection* SourceArrayLists::Selection(int association)
{
  return this->Selections[association];
}

void SourceArrayLists::ListArrays(vtkDataObject* data)
{
  // Every block's arrays (those not in all blocks are not projected, but
  // listing them keeps the selection stable when blocks change).
  this->Busy = true;
  for (vtkDataSet* source : DataSetsOf(data))
  {
    for (int association = 0; association < 2; ++association)
    {
      vtkDataSetAttributes* attributes = AttributesOf(source, association);
      vtkDataArraySelection* selection = this->Selections[association];
      for (int i = 0; i < attributes->GetNumberOfArrays(); ++i)
      {
        const char* name = attributes->GetArrayName(i);
        if (name && attributes->GetArray(i) && IsField(attributes, attributes->GetAbstractArray(i)))
        {
          this->Listed[association].insert(name);
          if (!selection->ArrayExists(name))
          {
            selection->AddArray(name, selection->GetUnknownArraySetting() != 0);
          }
        }
      }
    }
  }
  this->Busy = false;
}

void SourceArrayLists::List(vtkDataObject* data, vtkAlgorithm* producer)
{
  if (producer == this->ListedProducer.GetPointer())
  {
    this->ListArrays(data);
    return;
  }
  // Another Source (another producer, once its data has arrays): the names
  // listed from the previous one that it does not have leave the lists,
  // whatever their status. One producer's time steps and blocks keep every
  // name (an array may come back with the next step).
  const std::set<std::string> before[2] = { this->Listed[0], this->Listed[1] };
  this->Listed[0].clear();
  this->Listed[1].clear();
  this->ListArrays(data);
  if (this->Listed[0].empty() && this->Listed[1].empty())
  {
    // Not run yet (or no arrays): decided once it has some.
    this->Listed[0] = before[0];
    this->Listed[1] = before[1];
    return;
  }
  this->ListedProducer = producer;
  this->Busy = true;
  for (int association = 0; association < 2; ++association)
  {
    for (const std::string& name : before[association])
    {
      if (!this->Listed[association].count(name))
      {
        this->Selections[association]->RemoveArrayByName(name.c_str());
      }
    }
  }
  this->Busy = false;
}

void SourceArrayLists::ClearStatuses(int association)
{
  this->ListedAtList[association] = this->Listed[association];
  this->Named[association].clear();
  vtkDataArraySelection* selection = this->Selections[association];
  selection->RemoveAllArrays();
  selection->SetUnknownArraySetting(1);
}

void SourceArrayLists::SetStatus(int association, const char* name, int status)
{
  if (!name)
  {
    return;
  }
  this->Named[association].insert(name);
  vtkDataArraySelection* selection = this->Selections[association];
  selection->SetArraySetting(name, status);
  const std::set<std::string>& known = this->ListedAtList[association];
  const bool whole = !known.empty() &&
    std::includes(
      this->Named[association].begin(), this->Named[association].end(), known.begin(), known.end());
  selection->SetUnknownArraySetting(whole ? 1 : 0);
}
} // namespace mpvtk
