// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Labels.h"

#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"

#include "Adapter/FieldArrays.h"
#include "Adapter/SimplexMesh.h"
#include "Adapter/Threads.h"
#include "Parallel/Parts.h"
#include "Projection/Messages.h"
#include "Projection/Settings.h"
#include "Projection/SourceSide.h"

#include "Transfer/Space.h"

#include <algorithm>
#include <functional>
#include <sstream>
#include <string>

namespace mpvtk
{
namespace
{
/// Labels whose weights differ by less than this (relative) are a tie: round-off, not overlap.
constexpr double TieTolerance = 1e-12;

/// The Source array's value of source function f, of the operators' source space.
double LabelOf(const SimplexMesh& mesh, vtkDataArray* array, int association, bool dp1, mp::Index f)
{
  if (association == PointArrays)
  {
    return array->GetComponent(mesh.DataSetPoint(f), 0);
  }
  if (dp1)
  {
    const mp::MeshView& view = mesh.View();
    return array->GetComponent(view.ParentOf(f / view.CornersPerCell()), 0);
  }
  return array->GetComponent(f, 0);
}

/// The number of source functions of the operators of `association`.
mp::Index SourceFunctions(const mp::MeshView& view, int association, bool dp1)
{
  if (association == PointArrays)
  {
    return mp::SpaceSize(mp::SpaceType::P1, view);
  }
  return dp1 ? view.NumberOfCells * view.CornersPerCell() : mp::SpaceSize(mp::SpaceType::P0, view);
}

/// The label as a component name: an integer without a decimal point.
std::string LabelName(double label)
{
  std::ostringstream text;
  text.precision(17);
  text << label;
  return text.str();
}

/// The fill label in `array`'s type: FillLabel, or the type's largest value when it cannot hold it.
double FillLabelFor(vtkDataArray* array, int fill)
{
  const double value = static_cast<double>(fill);
  if (value < array->GetDataTypeMin() || value > array->GetDataTypeMax())
  {
    return array->GetDataTypeMax();
  }
  return value;
}

/// Row-wise w / sum(w) on valid rows (the NaN of a real label array has no label: not in the sum).
void Normalize(mp::LargeVector<double>& weights, int count, const std::vector<char>& valid)
{
  const vtkIdType rows = static_cast<vtkIdType>(valid.size());
  mpvtk::For(0, rows, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType f = begin; f < end; ++f)
    {
      double* w = weights.data() + f * count;
      double sum = 0;
      for (int k = 0; k < count && valid[f]; ++k)
      {
        sum += w[k];
      }
      if (sum > 0)
      {
        for (int k = 0; k < count; ++k)
        {
          w[k] /= sum;
        }
      }
    }
  });
}
} // namespace

bool HoldsIntegers(vtkDataArray* array)
{
  return array->GetDataType() != VTK_FLOAT && array->GetDataType() != VTK_DOUBLE;
}

bool IsLabelArray(
  vtkDataArray* array, const Settings& settings, int association, Messages* messages)
{
  if (settings.CategoricalMode == CategoricalAutomatic)
  {
    // (A vtkBitArray is a 0/1 indicator, whose projection is a covered fraction.)
    return HoldsIntegers(array) && array->GetNumberOfComponents() == 1 &&
      array->GetDataType() != VTK_BIT;
  }
  const char* name = array->GetName();
  if (!name || settings.CategoricalArrays.count(name) == 0)
  {
    return false;
  }
  if (array->GetNumberOfComponents() != 1 && messages)
  {
    const char* kind = association == PointArrays ? "point" : "cell";
    messages->WarnOnce(std::string("labels/") + kind + "/" + name,
      "Source " + std::string(kind) + " array '" + name +
        "' is named in CategoricalArrays but has " +
        std::to_string(array->GetNumberOfComponents()) +
        " components: only single-component arrays are labels; it is projected as numbers.");
  }
  return array->GetNumberOfComponents() == 1;
}

void ListPieceLabels(vtkDataSet* source, const Settings& settings, GatheredFields fields[2])
{
  for (int association = 0; source && association < 2; ++association)
  {
    vtkDataSetAttributes* data = AttributesOf(source, association);
    for (int i = 0; i < data->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* array = data->GetArray(i);
      if (!array || !array->GetName() || !IsField(data, array) ||
        !IsLabelArray(array, settings, association, nullptr))
      {
        continue;
      }
      std::vector<double> values(static_cast<size_t>(array->GetNumberOfTuples()));
      for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
      {
        values[static_cast<size_t>(t)] = array->GetComponent(t, 0);
      }
      fields[association].PieceLabels[array->GetName()] = SortedValues(std::move(values));
    }
  }
}

void IndexLabels(
  const SimplexMesh& mesh, int association, bool dp1, Parts& parts, GatheredFields& g)
{
  const bool reconstructed = association == CellArrays && dp1;
  const mp::Index n = SourceFunctions(mesh.View(), association, reconstructed);
  for (LabelField& field : g.Labels)
  {
    std::vector<double> values(static_cast<size_t>(n));
    mpvtk::For(0, n, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType f = begin; f < end; ++f)
      {
        values[f] = LabelOf(mesh, field.Array, association, reconstructed, f);
      }
    });
    // (Those of the Source piece this process had, too: the whole Source's labels.)
    const char* name = field.Array->GetName();
    const auto piece = name ? g.PieceLabels.find(name) : g.PieceLabels.end();
    if (piece != g.PieceLabels.end())
    {
      values.insert(values.end(), piece->second.begin(), piece->second.end());
    }
    field.Labels = parts.UnionOfValues(SortedValues(values));
    const std::vector<double>& labels = field.Labels;
    field.Which.assign(static_cast<size_t>(n), -1);
    mpvtk::For(0, n, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType f = begin; f < end; ++f)
      {
        const auto at = std::lower_bound(labels.begin(), labels.end(), values[f]);
        if (at != labels.end() && *at == values[f])
        {
          field.Which[f] = static_cast<int>(at - labels.begin());
        }
      }
    });
  }
}

Verdict ApplyLabels(LeafContext& ctx, const OperatorSet& ops, const mp::SolverHooks hooks[2],
  LeafSolutions& solutions)
{
  for (Transfer t : AllTransfers)
  {
    const GatheredFields& g = ctx.Source.Fields[SourceAssociation(t)];
    if (!ops.Operators[t] || g.Labels.empty())
    {
      continue;
    }
    const mp::MortarOperator& op = *ops.Operators[t];
    const mp::SolverHooks& hook = hooks[TargetSpaceOf(t) == mp::SpaceType::P1 ? 0 : 1];
    const size_t rows = static_cast<size_t>(op.GetNumberOfTargetFunctions());
    const std::vector<char>& valid = *solutions.System[t].Valid;
    solutions.Labels[t].resize(g.Labels.size());
    for (size_t i = 0; i < g.Labels.size(); ++i)
    {
      const LabelField& field = g.Labels[i];
      const int count = static_cast<int>(field.Labels.size());
      if (count == 0 ||
        static_cast<mp::Index>(field.Which.size()) != op.GetNumberOfSourceFunctions())
      {
        continue; // no label anywhere (every value NaN): the fill label everywhere
      }
      // The indicators chi_L side by side; M_ts chi_L / (its row sums), lumped.
      mp::LargeVector<double> indicators(field.Which.size() * static_cast<size_t>(count), 0.0);
      for (size_t f = 0; f < field.Which.size(); ++f)
      {
        if (field.Which[f] >= 0)
        {
          indicators[f * count + static_cast<size_t>(field.Which[f])] = 1.0;
        }
      }
      mp::LargeVector<double>& weights = solutions.Labels[t][i];
      weights.resize(rows * static_cast<size_t>(count));
      mp::ApplyOptions apply;
      apply.Mass = mp::MassType::Lumped;
      const mp::ApplyResult applied =
        op.Apply(indicators.data(), count, weights.data(), 0.0, apply, hook);
      if (!applied)
      {
        return Verdict::Fail(std::string("The labels of ") + TransferName(t) +
          " could not be projected: the operator lacks its overlap matrix M_ts.");
      }
      ctx.Stats.Solve += applied.Seconds;
      Normalize(weights, count, valid);
    }
  }
  return Verdict();
}

int WinningLabel(const double* weights, int count)
{
  double most = 0;
  for (int k = 0; k < count; ++k)
  {
    most = std::max(most, weights[k]);
  }
  if (!(most > 0))
  {
    return -1;
  }
  for (int k = 0; k < count; ++k)
  {
    if (weights[k] >= most * (1.0 - TieTolerance))
    {
      return k; // the smallest label of the tie
    }
  }
  return -1;
}

LabelOutput WriteLabelArray(const LabelField& field, const mp::LargeVector<double>& weights,
  const std::vector<char>& valid, vtkIdType n, const std::function<vtkIdType(vtkIdType)>& at,
  const std::string& name, const Settings& settings)
{
  const int count = static_cast<int>(field.Labels.size());
  const bool any = count > 0 && !weights.empty();
  LabelOutput out;
  out.Labels = vtkSmartPointer<vtkDataArray>::Take(field.Array->NewInstance());
  out.Labels->SetName(name.c_str());
  out.Labels->SetNumberOfComponents(1);
  out.Labels->SetNumberOfTuples(n);
  const double fill = FillLabelFor(field.Array, settings.FillLabel);
  // (One thread: any vtkDataArray, a vtkBitArray's shared bytes too.)
  for (vtkIdType f = 0; f < n; ++f)
  {
    const int k = any && valid[f] ? WinningLabel(weights.data() + f * count, count) : -1;
    out.Labels->SetComponent(at(f), 0, k >= 0 ? field.Labels[k] : fill);
  }
  if (!settings.LabelFractions)
  {
    return out;
  }
  vtkNew<vtkDoubleArray> fractions;
  fractions->SetName((name + "_Fractions").c_str());
  fractions->SetNumberOfComponents(std::max(count, 1));
  for (int k = 0; k < count; ++k)
  {
    fractions->SetComponentName(k, LabelName(field.Labels[k]).c_str());
  }
  fractions->SetNumberOfTuples(n);
  const double none = settings.Fill();
  double* to = fractions->GetPointer(0);
  const int width = fractions->GetNumberOfComponents();
  mpvtk::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType f = begin; f < end; ++f)
    {
      const vtkIdType row = at(f);
      for (int k = 0; k < width; ++k)
      {
        to[row * width + k] = any && valid[f] ? weights[f * count + k] : none;
      }
    }
  });
  out.Fractions = fractions;
  return out;
}
} // namespace mpvtk
