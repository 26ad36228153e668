// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Composite.h"

#include "vtkAppendFilter.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSet.h"
#include "vtkInformation.h"
#include "vtkDataSetAttributes.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"

#include "Adapter/CompositeLeaves.h"
#include "Adapter/DataSetChecks.h"
#include "Adapter/FieldArrays.h"
#include "Parallel/Parts.h"
#include "Projection/Messages.h"

#include <algorithm>

#include <set>

namespace mpvtk
{
vtkSmartPointer<vtkDataSet> AppendedSource(vtkDataObject* data, std::string& note, std::string& error)
{
  if (vtkDataSet* one = vtkDataSet::SafeDownCast(data))
  {
    return one;
  }
  vtkCompositeDataSet* composite = vtkCompositeDataSet::SafeDownCast(data);
  if (!composite)
  {
    return nullptr;
  }
  vtkNew<vtkAppendFilter> append;
  append->MergePointsOff();
  // Image and rectilinear blocks have no points of their own: computed in
  // double, not in vtkAppendFilter's default (float for such inputs).
  append->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  int leaves = 0;
  int skipped = 0;
  ForEachLeaf(composite, [&](vtkCompositeDataIterator* at) {
    vtkDataSet* leaf = vtkDataSet::SafeDownCast(at->GetCurrentDataObject());
    if (!leaf)
    {
      ++skipped;
      return;
    }
    if (leaf->GetNumberOfCells() == 0 || !error.empty())
    {
      return;
    }
    // vtkAppendFilter trusts the blocks' ids and arrays: checked first.
    const std::string block = "Source " + BlockName(at->GetCurrentFlatIndex(), nullptr);
    error = CheckDataSet(leaf, block);
    if (!error.empty())
    {
      return;
    }
    // Arrays with fewer tuples than points (cells) are left out of a copy.
    vtkSmartPointer<vtkDataSet> whole = leaf;
    for (int association = 0; association < 2; ++association)
    {
      const vtkIdType needed = association == 0 ? leaf->GetNumberOfPoints() : leaf->GetNumberOfCells();
      vtkDataSetAttributes* attributes = AttributesOf(whole, association);
      for (int a = attributes->GetNumberOfArrays() - 1; a >= 0; --a)
      {
        vtkAbstractArray* array = attributes->GetAbstractArray(a);
        if (array->GetNumberOfTuples() >= needed)
        {
          continue;
        }
        note += std::string(note.empty() ? "" : " ") + block + ": " +
          (association == 0 ? "point" : "cell") + " array '" +
          (array->GetName() ? array->GetName() : "(unnamed)") + "' has " +
          std::to_string(array->GetNumberOfTuples()) + " tuples for " + std::to_string(needed) +
          ": left out.";
        if (whole == leaf)
        {
          whole.TakeReference(leaf->NewInstance());
          whole->ShallowCopy(leaf);
          attributes = AttributesOf(whole, association);
        }
        attributes->RemoveArray(a);
      }
    }
    append->AddInputData(whole);
    ++leaves;
  });
  if (!error.empty())
  {
    return nullptr;
  }
  if (skipped)
  {
    note = std::to_string(skipped) + " Source blocks that are not datasets were skipped.";
  }
  if (leaves == 0)
  {
    return vtkSmartPointer<vtkUnstructuredGrid>::New();
  }
  append->Update();
  vtkDataSet* merged = append->GetOutput();
  // Arrays some blocks lack are not projected: say which.
  std::set<std::string> missing[2];
  for (int i = 0; i < append->GetNumberOfInputConnections(0); ++i)
  {
    vtkDataSet* leaf = vtkDataSet::SafeDownCast(append->GetInputDataObject(0, i));
    for (int association = 0; association < 2; ++association)
    {
      vtkDataSetAttributes* attributes = AttributesOf(leaf, association);
      for (int a = 0; a < attributes->GetNumberOfArrays(); ++a)
      {
        const char* name = attributes->GetArrayName(a);
        if (name && !AttributesOf(merged, association)->GetAbstractArray(name) &&
          std::string(name) != vtkDataSetAttributes::GhostArrayName())
        {
          missing[association].insert(name);
        }
      }
    }
  }
  for (int association = 0; association < 2; ++association)
  {
    if (!missing[association].empty())
    {
      note += std::string(note.empty() ? "" : " ") + "Source " +
        (association == 0 ? "point" : "cell") + " arrays not in every block of Source (or " +
        "not alike in all) are not projected:";
      for (const std::string& name : missing[association])
      {
        note += " '" + name + "'";
      }
      note += ".";
    }
  }
  return vtkSmartPointer<vtkDataSet>(merged);
}

std::vector<unsigned int> InputLeaves::FlatIndices() const
{
  std::vector<unsigned int> flat;
  for (const InputLeaf& leaf : this->Leaves)
  {
    flat.push_back(leaf.FlatIndex);
  }
  return flat;
}

namespace
{
/// Every leaf that any process has, in flat order; stand-ins for those this one lacks.
void CompleteAcrossProcesses(InputLeaves& leaves, Parts& parts)
{
  const std::vector<unsigned int> all = parts.Union(leaves.FlatIndices());
  std::vector<InputLeaf> complete;
  for (unsigned int flat : all)
  {
    auto found = std::find_if(leaves.Leaves.begin(), leaves.Leaves.end(),
      [flat](const InputLeaf& b) { return b.FlatIndex == flat; });
    if (found != leaves.Leaves.end())
    {
      complete.push_back(*found);
      continue;
    }
    vtkNew<vtkUnstructuredGrid> none, noneOut;
    leaves.StandIns.emplace_back(none.GetPointer());
    leaves.StandIns.emplace_back(noneOut.GetPointer());
    complete.push_back({ flat, none, noneOut, BlockName(flat, nullptr), false });
  }
  leaves.Leaves.swap(complete);
  std::vector<char> cells(leaves.Leaves.size(), 0);
  for (size_t i = 0; i < leaves.Leaves.size(); ++i)
  {
    cells[i] = leaves.Leaves[i].Target->GetNumberOfCells() > 0;
  }
  parts.Or(cells);
  for (size_t i = 0; i < leaves.Leaves.size(); ++i)
  {
    leaves.Leaves[i].EmptyEverywhere = !cells[i];
  }
}
} // namespace

InputLeaves LeavesOf(vtkDataObject* input, vtkDataObject* output, Parts& parts, Messages& say)
{
  InputLeaves leaves;
  vtkCompositeDataSet* composite = vtkCompositeDataSet::SafeDownCast(input);
  if (!composite)
  {
    if (vtkDataSet* one = vtkDataSet::SafeDownCast(input))
    {
      leaves.Leaves.push_back({ 0u, one, vtkDataSet::SafeDownCast(output), std::string(), false });
    }
    return leaves;
  }
  vtkCompositeDataSet* out = vtkCompositeDataSet::SafeDownCast(output);
  int notDataSets = 0;
  ForEachLeaf(composite, [&](vtkCompositeDataIterator* at) {
    vtkDataSet* leaf = vtkDataSet::SafeDownCast(at->GetCurrentDataObject());
    if (!leaf)
    {
      ++notDataSets;
      return;
    }
    leaves.Leaves.push_back({ at->GetCurrentFlatIndex(), leaf,
      vtkDataSet::SafeDownCast(out->GetDataSet(at)), BlockName(at), false });
  });
  if (notDataSets)
  {
    say.Warn(std::to_string(notDataSets) + " Input blocks that are not datasets were skipped.");
  }
  CompleteAcrossProcesses(leaves, parts);
  return leaves;
}
} // namespace mpvtk
