// SPDX-License-Identifier: BSD-3-Clause
#include "Adapter/PieceArrays.h"

#include "Adapter/FieldArrays.h"

#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkSetGet.h"
#include "vtkType.h"

#include <tuple>

namespace mpvtk
{
std::vector<PieceField> FieldsOfPiece(vtkDataSet* data)
{
  std::vector<PieceField> fields;
  for (int association = 0; association < 2; ++association)
  {
    vtkDataSetAttributes* attributes = AttributesOf(data, association);
    for (int i = 0; i < attributes->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* a = attributes->GetArray(i);
      if (a && a->GetName() && IsField(attributes, a))
      {
        fields.push_back(
          { association, a->GetName(), a->GetDataType(), a->GetNumberOfComponents() });
      }
    }
  }
  return fields;
}

namespace
{
/// "3 components of double".
std::string Kind(int type, int components)
{
  return std::to_string(components) + (components == 1 ? " component of " : " components of ") +
    vtkImageScalarTypeNameMacro(type);
}

/// "a, b and c".
std::string Listed(const std::vector<std::string>& items)
{
  std::string text;
  for (size_t i = 0; i < items.size(); ++i)
  {
    text += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  }
  return text;
}
} // namespace

JoinedFields JoinPieceFields(const std::vector<std::vector<PieceField>>& pieces,
  const std::vector<std::string>& names, const std::string& whole)
{
  // Per association and name: per (type, components), the pieces that hold it so.
  using Variants = std::map<std::pair<int, int>, std::vector<size_t>>;
  std::map<std::string, Variants> seen[2];
  for (size_t i = 0; i < pieces.size(); ++i)
  {
    for (const PieceField& f : pieces[i])
    {
      std::vector<size_t>& holders = seen[f.Association][f.Name][{ f.Type, f.Components }];
      if (holders.empty() || holders.back() != i) // (a name twice in one piece counts once)
      {
        holders.push_back(i);
      }
    }
  }
  JoinedFields joined;
  for (int association = 0; association < 2; ++association)
  {
    const std::string label =
      std::string("Source ") + (association == 0 ? "point" : "cell") + " array '";
    for (const auto& byName : seen[association])
    {
      const std::string& name = byName.first;
      const Variants& variants = byName.second;
      if (variants.size() > 1)
      {
        std::vector<std::string> how;
        for (const auto& v : variants)
        {
          std::vector<std::string> on;
          for (size_t i : v.second)
          {
            on.push_back(names[i]);
          }
          how.push_back(Kind(v.first.first, v.first.second) + " on " + Listed(on));
        }
        joined.Warnings[association][name] =
          (label + name + "' is not projected: it differs between the Source " + whole + " (" +
            Listed(how) + "). Make it alike on all of them (or rename one).");
        continue;
      }
      const int type = variants.begin()->first.first;
      const int components = variants.begin()->first.second;
      const std::vector<size_t>& holders = variants.begin()->second;
      if (holders.size() == pieces.size())
      {
        joined.Kept[association][name] = { association, name, type, components };
        continue;
      }
      // Missing on some pieces: a hole there (NaN), which an integer cannot hold.
      const bool real = type == VTK_FLOAT || type == VTK_DOUBLE;
      joined.Kept[association][name] = { association, name, real ? type : VTK_DOUBLE, components };
      joined.Holes[association].insert(name);
      std::vector<std::string> without;
      for (size_t i = 0, k = 0; i < pieces.size(); ++i)
      {
        if (k < holders.size() && holders[k] == i)
        {
          ++k;
          continue;
        }
        without.push_back(names[i]);
      }
      joined.Warnings[association][name] = (label + name + "' is missing on " + Listed(without) +
        ": it is projected from the Source " + whole +
        " that have it, the Source cells without it " +
        "being a hole in Source for it, as NaN values are (its values there are NaN" +
        (real ? "" : "; it is joined as double") + "). Input points and cells left without " +
        "data for it get the fill value and are marked invalid (in vtkValidPointMask and " +
        "vtkValidCellMask, or in masks of its own when the arrays' masks differ).");
    }
  }
  return joined;
}
} // namespace mpvtk
