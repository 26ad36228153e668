// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Labels.h"

#include "vtkDataArray.h"
#include "vtkDataArraySelection.h"
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

/// A label's fraction from its weight w and its row's sum of weights: w / sum
/// (a row without weight, or invalid, keeps w).
double Fraction(double w, double sum)
{
  return sum > 0 ? w / sum : w;
}

/// Whether fraction v of a row whose largest fraction is top (> 0) is in its tie.
bool InTie(double v, double top)
{
  return v >= top * (1.0 - TieTolerance);
}

/// The labels of the block that starts at label `first`: LabelBlock, but never
/// one label of several (a single column is multiplied in another order).
int BlockWidth(int first, int count)
{
  const int left = count - first;
  if (left <= LabelBlock)
  {
    return left;
  }
  return left == LabelBlock + 1 ? LabelBlock - 1 : LabelBlock;
}

/// The weights w_iL (rows x width) of labels first .. first + width - 1:
/// their indicators projected by `op` with `mass`: lumped (on second-order
/// targets in their Bernstein form, bounded), or consistent on
/// second-order targets without one (which have no lumped mass), negative
/// weights cut.
/// Collective.
mp::ApplyResult ProjectBlock(const mp::MortarOperator& op, const mp::SolverHooks& hook,
  const LabelField& field, int first, int width, const mp::ApplyOptions& base,
  mp::LargeVector<double>& weights)
{
  mp::LargeVector<double> indicators(field.Which.size() * static_cast<size_t>(width), 0.0);
  for (size_t f = 0; f < field.Which.size(); ++f)
  {
    const int k = field.Which[f] - first;
    if (k >= 0 && k < width)
    {
      indicators[f * width + static_cast<size_t>(k)] = 1.0;
    }
  }
  weights.resize(static_cast<size_t>(op.GetNumberOfTargetFunctions()) * width);
  mp::ApplyOptions apply = base;
  if (base.Mass == mp::MassType::Lumped && !op.HasNodalTarget())
  {
    return op.Apply(indicators.data(), width, weights.data(), 0.0, apply, hook);
  }
  // A second-order target's lumped weights are means of the indicators'
  // fields, which a second-order Source's quadratic functions take below 0
  // and above 1 next to a region's edge: bounded (each label's measure
  // kept), then cut at 0 as the consistent projection is.
  apply.Bounded = base.Mass == mp::MassType::Lumped;
  // The consistent projection overshoots: cut at zero, so that the
  // fractions stay in [0, 1].
  const mp::ApplyResult result =
    op.Apply(indicators.data(), width, weights.data(), 0.0, apply, hook);
  for (double& w : weights)
  {
    w = std::max(w, 0.0);
  }
  return result;
}

/**
 * Pass 2 of SolveLabels for the block of labels first .. first + width - 1,
 * from their weights (row f's label first + k at w[f * stride + k]): the
 * winner of each row, the smallest label whose fraction is in the tie of
 * the largest, and the fractions when `fractions` (w may be those
 * fractions' own storage, each weight replaced by its fraction).
 */
void DecideBlock(const double* w, size_t stride, int first, int width, int count,
  const std::vector<double>& sum, const std::vector<double>& most, const std::vector<char>& valid,
  bool fractions, LabelSolution& out)
{
  const vtkIdType rows = static_cast<vtkIdType>(valid.size());
  mpvtk::For(0, rows, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType f = begin; f < end; ++f)
    {
      const double top = Fraction(most[f], sum[f]);
      for (int k = 0; k < width; ++k)
      {
        const double v = Fraction(w[f * stride + k], sum[f]);
        if (fractions)
        {
          out.Fractions[f * count + first + k] = v;
        }
        if (valid[f] && top > 0 && out.Winner[f] < 0 && InTie(v, top))
        {
          out.Winner[f] = first + k; // the smallest label of the tie
        }
      }
    }
  });
}

/**
 * One label array on one operator, block by block. First pass: per row
 * the sum of its weights in label order and the largest weight (w / sum
 * is monotone in w: the largest fraction is the largest weight's). Second
 * pass (DecideBlock): the winner and the fractions when `fractions`. With
 * several blocks the second pass projects the blocks again, unless it has
 * the fractions: their storage (rows x labels) keeps the first pass's
 * weights. Collective.
 */
bool SolveLabels(const mp::MortarOperator& op, const mp::SolverHooks& hook, const LabelField& field,
  const std::vector<char>& valid, bool fractions, const mp::ApplyOptions& base, LabelSolution& out,
  double& seconds)
{
  const int count = static_cast<int>(field.Labels.size());
  const vtkIdType rows = static_cast<vtkIdType>(valid.size());
  const bool blocks = BlockWidth(0, count) < count;
  const bool keep = blocks && fractions; // the weights kept in out.Fractions
  std::vector<double> sum(valid.size(), 0.0);
  std::vector<double> most(valid.size(), 0.0);
  out.Winner.assign(valid.size(), -1);
  out.Fractions.resize(fractions ? valid.size() * static_cast<size_t>(count) : 0);
  mp::LargeVector<double> weights;
  for (int first = 0, width = 0; first < count; first += width)
  {
    width = BlockWidth(first, count);
    const mp::ApplyResult applied = ProjectBlock(op, hook, field, first, width, base, weights);
    if (!applied)
    {
      return false;
    }
    seconds += applied.Seconds;
    mpvtk::For(0, rows, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType f = begin; f < end; ++f)
      {
        for (int k = 0; k < width; ++k)
        {
          const double w = weights[f * width + k];
          sum[f] += valid[f] ? w : 0.0;
          most[f] = std::max(most[f], w);
          if (keep)
          {
            out.Fractions[f * count + first + k] = w;
          }
        }
      }
    });
  }
  for (int first = 0, width = 0; first < count; first += width)
  {
    width = BlockWidth(first, count);
    if (keep)
    {
      DecideBlock(out.Fractions.data() + first, static_cast<size_t>(count), first, width, count,
        sum, most, valid, fractions, out);
      continue;
    }
    if (blocks)
    {
      const mp::ApplyResult applied = ProjectBlock(op, hook, field, first, width, base, weights);
      if (!applied)
      {
        return false;
      }
      seconds += applied.Seconds;
    }
    DecideBlock(weights.data(), static_cast<size_t>(width), first, width, count, sum, most, valid,
      fractions, out);
  }
  return true;
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

void ListPieceLabels(vtkDataSet* source, vtkDataArraySelection* const selections[2],
  const Settings& settings, GatheredFields fields[2])
{
  for (int association = 0; source && association < 2; ++association)
  {
    vtkDataSetAttributes* data = AttributesOf(source, association);
    for (int i = 0; i < data->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* array = data->GetArray(i);
      if (!array || !array->GetName() || !IsField(data, array) ||
        !selections[association]->ArrayIsEnabled(array->GetName()) ||
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

namespace
{
/**
 * Whether some process alone has more than MaximumAutomaticLabels distinct
 * values of `field` (`mine` here): then its Distinct is the largest such
 * count (the whole Source's when one process has every value, else a lower
 * bound: AtLeast). Collective.
 */
bool IsIdArray(size_t mine, Parts& parts, LabelField& field)
{
  double counts[2] = { -static_cast<double>(mine), static_cast<double>(mine) }; // largest, sum
  parts.Minimum(counts, 1);
  parts.Sum(counts + 1, 1);
  const double largest = -counts[0];
  if (!(largest > static_cast<double>(MaximumAutomaticLabels)))
  {
    return false;
  }
  field.Distinct = static_cast<size_t>(largest);
  field.AtLeast = counts[1] > largest;
  return true;
}
} // namespace

void IndexLabels(const SimplexMesh& mesh, int association, bool dp1, bool automatic, Parts& parts,
  GatheredFields& g)
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
    std::vector<double> mine = SortedValues(values);
    if (automatic && IsIdArray(mine.size(), parts, field))
    {
      continue;
    }
    field.Labels = parts.UnionOfValues(mine);
    field.Distinct = field.Labels.size();
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

void CheckLabelCounts(
  int association, const Settings& settings, Messages& messages, GatheredFields& g)
{
  const char* kind = association == PointArrays ? "point" : "cell";
  const bool automatic = settings.CategoricalMode == CategoricalAutomatic;
  for (size_t i = 0; i < g.Labels.size();)
  {
    const LabelField& field = g.Labels[i];
    if (field.Distinct <= MaximumAutomaticLabels)
    {
      ++i;
      continue;
    }
    const std::string label = field.Array->GetName() ? field.Array->GetName() : "(unnamed)";
    const std::string count = (field.AtLeast ? "at least " : "") + std::to_string(field.Distinct);
    if (!automatic)
    {
      // (Named by the user: projected, in time that grows with the number of labels.)
      messages.WarnOnce(std::string("many/") + kind + "/" + label,
        "Source " + std::string(kind) + " label array '" + label + "' has " + count +
          " labels: they are projected " + std::to_string(LabelBlock) +
          " at a time, in time that grows with their number.");
      ++i;
      continue;
    }
    messages.WarnOnce(std::string("ids/") + kind + "/" + label, // once per array, not per step
      "Source " + std::string(kind) + " array '" + label + "' looks like an id array (" + count +
        " distinct values, more than " + std::to_string(MaximumAutomaticLabels) +
        "): projected as numbers; deselect it, or name it in CategoricalArrays with "
        "CATEGORICAL_SELECTED to project it as labels.");
    g.AddArray(field.Array, label, false);
    g.Labels.erase(g.Labels.begin() + static_cast<std::ptrdiff_t>(i));
  }
}

bool WritesFractions(const LabelField& field, const Settings& settings)
{
  return settings.LabelFractions && field.Labels.size() <= MaximumLabelFractions;
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
    solutions.Labels[t].resize(g.Labels.size());
    for (size_t i = 0; i < g.Labels.size(); ++i)
    {
      const LabelField& field = g.Labels[i];
      if (field.Labels.empty() ||
        static_cast<mp::Index>(field.Which.size()) != op.GetNumberOfSourceFunctions())
      {
        continue; // no label anywhere (every value NaN): the fill label everywhere
      }
      const bool fractions = WritesFractions(field, ctx.Options);
      if (ctx.Options.LabelFractions && !fractions)
      {
        const std::string name = field.Array->GetName() ? field.Array->GetName() : "(unnamed)";
        const std::string kind = SourceAssociation(t) == PointArrays ? "point" : "cell";
        ctx.Say.WarnOnce("fractions/" + kind + "/" + name,
          "Source " + kind + " label array '" + name + "' has " +
            std::to_string(field.Labels.size()) + " labels, more than " +
            std::to_string(MaximumLabelFractions) + ": no '" + name +
            "_Fractions' array (one component per label); its labels are projected.");
      }
      // (Second-order Input cells without a Bernstein form on any process:
      // consistent everywhere.)
      const bool nodal = ctx.Shape.SecondOrder && !ctx.Shape.Bernstein;
      mp::ApplyOptions base;
      base.Mass = nodal && TargetSpaceOf(t) == mp::SpaceType::P1 ? mp::MassType::Consistent
                                                                 : mp::MassType::Lumped;
      base.Signed = ctx.Shape.Signed;
      if (!SolveLabels(op, hook, field, *solutions.System[t].Valid, fractions, base,
            solutions.Labels[t][i], ctx.Stats.Solve))
      {
        return Verdict::Fail(std::string("The labels of ") + TransferName(t) +
          " could not be projected: the operator lacks its overlap matrix M_ts.");
      }
    }
  }
  return Verdict();
}

LabelOutput WriteLabelArray(const LabelField& field, const LabelSolution& solution,
  const std::vector<char>& valid, vtkIdType n, const std::function<vtkIdType(vtkIdType)>& at,
  const std::string& name, const Settings& settings)
{
  const int count = static_cast<int>(field.Labels.size());
  const bool any = count > 0 && !solution.Winner.empty();
  LabelOutput out;
  out.Labels = vtkSmartPointer<vtkDataArray>::Take(field.Array->NewInstance());
  out.Labels->SetName(name.c_str());
  out.Labels->SetNumberOfComponents(1);
  out.Labels->SetNumberOfTuples(n);
  const double fill = FillLabelFor(field.Array, settings.FillLabel);
  // (One thread: any vtkDataArray, a vtkBitArray's shared bytes too.)
  for (vtkIdType f = 0; f < n; ++f)
  {
    const int k = any && valid[f] ? solution.Winner[f] : -1;
    out.Labels->SetComponent(at(f), 0, k >= 0 ? field.Labels[k] : fill);
  }
  if (!WritesFractions(field, settings))
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
        to[row * width + k] = any && valid[f] ? solution.Fractions[f * count + k] : none;
      }
    }
  });
  out.Fractions = fractions;
  return out;
}
} // namespace mpvtk
