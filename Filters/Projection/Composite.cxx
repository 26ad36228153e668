// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Composite.h"

#include "vtkAppendFilter.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkInformation.h"
#include "vtkDataSetAttributes.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"

#include "Adapter/CompositeLeaves.h"
#include "Adapter/DataSetChecks.h"
#include "Adapter/FieldArrays.h"
#include "Adapter/PieceArrays.h"
#include "Parallel/Parts.h"
#include "Projection/Messages.h"

#include <algorithm>
#include <limits>

#include <set>

namespace mpvtk
{
namespace
{
/// `leaf` without its arrays that have fewer tuples than points (cells):
/// a copy when it has any (said in `note`), else itself.
vtkSmartPointer<vtkDataSet> WithoutShortArrays(
  vtkDataSet* leaf, const std::string& block, std::string& note)
{
  vtkSmartPointer<vtkDataSet> whole = leaf;
  for (int association = 0; association < 2; ++association)
  {
    const vtkIdType needed =
      association == 0 ? leaf->GetNumberOfPoints() : leaf->GetNumberOfCells();
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
  return whole;
}

/**
 * `block` made to join the others by PieceArrays.h's rule: its fields
 * that are refused removed, those kept with a hole in their joined type
 * (an integer one as double), or all NaN where it lacks them. A copy
 * when anything changes, else itself.
 */
vtkSmartPointer<vtkDataSet> Joinable(vtkDataSet* block, const JoinedFields& joined)
{
  vtkSmartPointer<vtkDataSet> out = block;
  auto own = [&]() {
    if (out == block)
    {
      out.TakeReference(block->NewInstance());
      out->ShallowCopy(block);
    }
  };
  for (int association = 0; association < 2; ++association)
  {
    const vtkIdType tuples =
      association == 0 ? block->GetNumberOfPoints() : block->GetNumberOfCells();
    for (const PieceField& f : FieldsOfPiece(block))
    {
      if (f.Association == association && !joined.Kept[association].count(f.Name))
      {
        own();
        AttributesOf(out, association)->RemoveArray(f.Name.c_str());
      }
    }
    for (const std::string& name : joined.Holes[association])
    {
      const PieceField& kept = joined.Kept[association].at(name);
      vtkDataArray* has = AttributesOf(out, association)->GetArray(name.c_str());
      if (has && has->GetDataType() == kept.Type)
      {
        continue;
      }
      vtkSmartPointer<vtkDataArray> array;
      array.TakeReference(vtkDataArray::CreateDataArray(kept.Type));
      array->SetName(name.c_str());
      array->SetNumberOfComponents(kept.Components);
      array->SetNumberOfTuples(tuples);
      if (has)
      {
        array->DeepCopy(has); // (an integer field as double)
      }
      else
      {
        array->Fill(std::numeric_limits<double>::quiet_NaN());
      }
      own();
      AttributesOf(out, association)->AddArray(array); // (replaces one of the same name)
    }
  }
  return out;
}

/// The names of arrays of the appended blocks that the append left out
/// (vtkAppendFilter keeps those every block has alike): said, not dropped silently.
std::string LeftOutByAppend(vtkAppendFilter* append, vtkDataSet* merged)
{
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
  std::string note;
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
  return note;
}
} // namespace

vtkSmartPointer<vtkDataSet> AppendedSource(
  vtkDataObject* data, std::string& note, std::string& error, JoinedFields& joined)
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
  std::vector<vtkSmartPointer<vtkDataSet>> blocks;
  std::vector<std::string> names;
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
    blocks.push_back(WithoutShortArrays(leaf, block, note));
    names.push_back(BlockName(at));
  });
  if (!error.empty())
  {
    return nullptr;
  }
  if (skipped)
  {
    note = std::to_string(skipped) + " Source blocks that are not datasets were skipped.";
  }
  if (blocks.empty())
  {
    return vtkSmartPointer<vtkUnstructuredGrid>::New();
  }
  // Fields that differ between the blocks: PieceArrays.h's rule.
  std::vector<std::vector<PieceField>> fields;
  for (const auto& block : blocks)
  {
    fields.push_back(FieldsOfPiece(block));
  }
  joined = JoinPieceFields(fields, names, "blocks");
  vtkNew<vtkAppendFilter> append;
  append->MergePointsOff();
  // Image and rectilinear blocks have no points of their own: computed in
  // double, not in vtkAppendFilter's default (float for such inputs).
  append->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  for (const auto& block : blocks)
  {
    append->AddInputData(Joinable(block, joined));
  }
  append->Update();
  vtkDataSet* merged = append->GetOutput();
  const std::string lost = LeftOutByAppend(append, merged);
  note += std::string(note.empty() || lost.empty() ? "" : " ") + lost;
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
