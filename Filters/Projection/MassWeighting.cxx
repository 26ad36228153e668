// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/MassWeighting.h"

#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"

#include "Parallel/Parts.h"
#include "Projection/Apply.h"
#include "Projection/Messages.h"
#include "Projection/Settings.h"
#include "Projection/SourceSide.h"
#include "Adapter/FieldArrays.h"
#include "Adapter/Threads.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpvtk
{
namespace
{
const char* KindOf(int association)
{
  return association == 0 ? "point" : "cell";
}

/// Index of the array named `name` among g's, or -1.
int Find(const GatheredFields& g, const std::string& name)
{
  for (int a = 0; a < static_cast<int>(g.Arrays.size()); ++a)
  {
    const char* own = g.Arrays[a]->GetName();
    if (own && name == own)
    {
      return a;
    }
  }
  return -1;
}

/// Whether Source's data of `association` has a field named `name`.
bool HasField(vtkDataSet* source, int association, const std::string& name)
{
  vtkDataSetAttributes* data = AttributesOf(source, association);
  vtkAbstractArray* array = data->GetAbstractArray(name.c_str());
  return array && IsField(data, array);
}

/**
 * The arrays of g to weight (density `d`): every array but the density
 * and hidden ones when the list is empty, else the named ones found (the
 * others said by name).
 */
std::vector<int> WeightedArrays(const Settings& settings, int association, vtkDataSet* source,
  int d, Messages& messages, const GatheredFields& g)
{
  std::vector<int> weighted;
  if (settings.MassWeightedArrays.empty())
  {
    for (int a = 0; a < static_cast<int>(g.Arrays.size()); ++a)
    {
      if (a != d && !g.Hidden[a])
      {
        weighted.push_back(a);
      }
    }
    return weighted;
  }
  const std::string density = settings.DensityArray;
  for (const std::string& name : settings.MassWeightedArrays)
  {
    const int a = Find(g, name);
    if (a == d)
    {
      messages.WarnOnce("massweight/self/" + name,
        "MassWeightedArrays names the density '" + name + "' itself: it is projected as it is.");
    }
    else if (a >= 0)
    {
      if (std::find(weighted.begin(), weighted.end(), a) == weighted.end())
      {
        weighted.push_back(a);
      }
    }
    else if (HasField(source, association, name))
    {
      messages.WarnOnce("massweight/unselected/" + name,
        "MassWeightedArrays names the Source " + std::string(KindOf(association)) + " array '" +
          name + "', which is not projected (not selected, or not numeric).");
    }
    else if (!HasField(source, 1 - association, name))
    {
      messages.WarnOnce("massweight/missing/" + name,
        "MassWeightedArrays names '" + name + "', which is not an array of Source.");
    }
  }
  return weighted;
}

/// The named arrays of g that another association's density (or none) leaves unweighted, said.
void WarnUnweighted(const Settings& settings, int association, int densityAssociation,
  Messages& messages, const GatheredFields& g)
{
  std::vector<std::string> names = settings.MassWeightedArrays;
  if (names.empty() && densityAssociation >= 0)
  {
    return; // (every array of the density's association: none of this one)
  }
  for (const std::string& name : names)
  {
    if (Find(g, name) < 0)
    {
      continue;
    }
    const std::string why = densityAssociation < 0
      ? "there is no usable density"
      : "the density '" + settings.DensityArray + "' is " + KindOf(densityAssociation) + " data";
    messages.WarnOnce("massweight/other/" + name,
      "MassWeightedArrays: the Source " + std::string(KindOf(association)) + " array '" + name +
        "' is projected without mass weighting: " + why + ".");
  }
}

/**
 * The density's scale and the weighted arrays' ranges, over every process
 * (one reduction): false, said, when the density has no finite non-zero value.
 */
bool MeasureRanges(const Settings& settings, Parts& parts, Messages& messages, GatheredFields& g)
{
  MassWeights& mass = g.Mass;
  const int width = g.Components;
  const size_t functions = g.Values.size() / static_cast<size_t>(std::max(width, 1));
  std::vector<double> least(1, 0.0); // -scale, then per component low, then -high
  std::vector<double> high;
  const int densityColumn = g.Offsets[mass.Density];
  for (size_t f = 0; f < functions; ++f)
  {
    const double rho = g.Values[f * width + densityColumn];
    least[0] = std::isfinite(rho) ? std::min(least[0], -std::abs(rho)) : least[0];
  }
  for (int a : mass.Weighted)
  {
    for (int k = 0; k < g.Arrays[a]->GetNumberOfComponents(); ++k)
    {
      double lo = std::numeric_limits<double>::infinity();
      double hi = -lo;
      for (size_t f = 0; f < functions; ++f)
      {
        const double q = g.Values[f * width + g.Offsets[a] + k];
        lo = std::isfinite(q) ? std::min(lo, q) : lo;
        hi = std::isfinite(q) ? std::max(hi, q) : hi;
      }
      least.push_back(lo);
      high.push_back(-hi);
    }
  }
  least.insert(least.end(), high.begin(), high.end());
  parts.Minimum(least.data(), static_cast<int>(least.size()));
  const size_t n = high.size();
  mass.Scale = -least[0];
  mass.Low.assign(least.begin() + 1, least.begin() + 1 + static_cast<long>(n));
  mass.High.resize(n);
  for (size_t i = 0; i < n; ++i)
  {
    mass.High[i] = -least[1 + n + i];
  }
  if (mass.Scale > 0 && std::isfinite(mass.Scale))
  {
    return true;
  }
  messages.WarnOnce("massweight/nodensity/" + settings.DensityArray,
    "DensityArray '" + settings.DensityArray +
      "' has no finite non-zero value: the arrays are projected without mass weighting.");
  return false;
}

/// The weighted arrays' Source values times the density (NaN where either is).
void Multiply(GatheredFields& g)
{
  const MassWeights& mass = g.Mass;
  const int width = g.Components;
  const vtkIdType functions =
    static_cast<vtkIdType>(g.Values.size() / static_cast<size_t>(std::max(width, 1)));
  const int densityColumn = g.Offsets[mass.Density];
  mpvtk::For(0, functions, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType f = begin; f < end; ++f)
    {
      const double rho = g.Values[f * width + densityColumn];
      for (int a : mass.Weighted)
      {
        for (int k = 0; k < g.Arrays[a]->GetNumberOfComponents(); ++k)
        {
          g.Values[f * width + g.Offsets[a] + k] *= rho;
        }
      }
    }
  });
}
} // namespace

int ProductOffset(const GatheredFields& g, int w)
{
  int offset = 0;
  for (int v = 0; v < w; ++v)
  {
    offset += g.Arrays[g.Mass.Weighted[static_cast<size_t>(v)]]->GetNumberOfComponents();
  }
  return offset;
}

int ProductWidth(const GatheredFields& g)
{
  return ProductOffset(g, static_cast<int>(g.Mass.Weighted.size()));
}

int MassWeights::WeightedIndex(int a) const
{
  const auto at = std::find(this->Weighted.begin(), this->Weighted.end(), a);
  return at == this->Weighted.end() ? -1 : static_cast<int>(at - this->Weighted.begin());
}

int DensityAssociation(vtkDataSet* source, const Settings& settings, Messages& messages)
{
  const std::string& name = settings.DensityArray;
  if (name.empty())
  {
    return -1;
  }
  for (int association = 0; association < 2; ++association)
  {
    if (!HasField(source, association, name))
    {
      continue;
    }
    vtkDataArray* array = AttributesOf(source, association)->GetArray(name.c_str());
    if (!array || array->GetNumberOfComponents() != 1)
    {
      messages.WarnOnce("massweight/density/" + name,
        "DensityArray '" + name + "' is not one-component numeric " + KindOf(association) +
          " data: no array is mass-weighted (a density has one component).");
      return -1;
    }
    return association;
  }
  messages.WarnOnce("massweight/density/" + name,
    "DensityArray '" + name +
      "' is not an array of Source's point or cell data: no array is mass-weighted.");
  return -1;
}

void WeighSourceFields(const Settings& settings, int association, int densityAssociation,
  vtkDataSet* source, Parts& parts, Messages& messages, GatheredFields& g)
{
  g.Mass = MassWeights();
  if (settings.DensityArray.empty())
  {
    return;
  }
  if (association != densityAssociation)
  {
    WarnUnweighted(settings, association, densityAssociation, messages, g);
    return;
  }
  if (association == CellArrays && settings.Extensive)
  {
    messages.WarnOnce("massweight/extensive",
      "DensityArray '" + settings.DensityArray +
        "' is cell data and cell arrays are EXTENSIVE (totals per cell): mass weighting is for "
        "intensive arrays; none is mass-weighted.");
    return;
  }
  const int d = Find(g, settings.DensityArray);
  if (d < 0)
  {
    return; // (not gathered: too short, said by the gathering)
  }
  g.Mass.Density = d;
  g.Mass.Weighted = WeightedArrays(settings, association, source, d, messages, g);
  if (g.Mass.Weighted.empty() || !MeasureRanges(settings, parts, messages, g))
  {
    g.Mass = MassWeights();
    return;
  }
  Multiply(g);
  // (A warm start from a solution of q itself would start far off.)
  g.Key += "/weighted by " + settings.DensityArray + ":";
  for (int a : g.Mass.Weighted)
  {
    g.Key += std::to_string(a) + ",";
  }
}

namespace
{
/**
 * The w-th weighted array of transfer t: its projected product put aside
 * (solutions.Products), then the ratio, guarded (solutions.Guarded) and
 * clipped, on its valid functions. Returns how many functions the guard
 * left (points: those this process counts).
 */
vtkIdType Divide(LeafContext& ctx, const GatheredFields& g, int w, Transfer t,
  const mp::SolverHooks& hook, LeafSolutions& solutions)
{
  const MassWeights& mass = g.Mass;
  const int a = mass.Weighted[static_cast<size_t>(w)];
  const int nc = g.Arrays[a]->GetNumberOfComponents();
  const int width = g.Components;
  mp::LargeVector<double>& values = solutions.Values[t];
  const std::vector<char>& valid = *solutions.ByArray[t][static_cast<size_t>(a)].Valid;
  const std::vector<char>& densityValid =
    *solutions.ByArray[t][static_cast<size_t>(mass.Density)].Valid;
  const double guard = DensityGuard * mass.Scale;
  const bool clip = ctx.Options.PreserveBounds;
  const int first = ProductOffset(g, w); // its columns in Products, its components in Low, High
  const int productWidth = ProductWidth(g);
  const size_t rows = values.size() / static_cast<size_t>(width);
  const size_t points = static_cast<size_t>(ctx.TargetData->GetNumberOfPoints());
  const bool onPoints = TargetSpaceOf(t) == mp::SpaceType::P1;
  std::vector<char>& guarded = solutions.Guarded[t][static_cast<size_t>(w)];
  guarded.assign(rows, 0);
  vtkIdType count = 0;
  // Any guarded function, counted here or not (a shared point another
  // process counts is guarded on this one too: the extension must not read it).
  bool anyGuarded = false;
  for (size_t f = 0; f < rows; ++f)
  {
    double* q = &values[f * width + g.Offsets[a]];
    std::copy(q, q + nc, &solutions.Products[t][f * productWidth + first]);
    if (!valid[f])
    {
      continue;
    }
    const double rho = values[f * width + g.Offsets[mass.Density]];
    const bool divides = densityValid[f] && rho > guard;
    if (!divides)
    {
      guarded[f] = 1;
      anyGuarded = true;
      const bool counted = !onPoints || (f < points && (!hook.Counted || hook.Counted[f]));
      count += counted ? 1 : 0;
    }
    for (int k = 0; k < nc; ++k)
    {
      // A guarded function is written as the fill value (Outputs.cxx); it
      // holds a finite value in q's range, which the extrapolation does
      // not read (no value of q: Extrapolation.cxx, NarrowedReads).
      const double ratio =
        divides ? q[k] / rho : (densityValid[f] && std::isfinite(q[k]) ? q[k] / guard : 0.0);
      q[k] = clip || !divides ? std::min(std::max(ratio, mass.Low[first + k]), mass.High[first + k])
                              : ratio;
    }
  }
  if (!anyGuarded)
  {
    guarded.clear();
  }
  return count;
}

/// Says (once, by process 0) how many functions the guard left for array a of transfer t.
void WarnGuarded(LeafContext& ctx, const GatheredFields& g, int a, Transfer t, double count)
{
  const bool onPoints = TargetSpaceOf(t) == mp::SpaceType::P1;
  const std::string name = g.Arrays[a]->GetName() ? g.Arrays[a]->GetName() : "(unnamed)";
  if (count == 0 || ctx.Processes.Rank() != 0)
  {
    return;
  }
  ctx.Say.WarnOnce("massweight/guard/" + ctx.Role + "/" + TransferName(t) + "/" + name,
    std::to_string(static_cast<long long>(count)) + " " + ctx.Role +
      (onPoints ? " points" : " cells") + " have a projected density '" + ctx.Options.DensityArray +
      "' of at most 1e-10 times the Source's largest |density|: the mass-weighted array '" + name +
      "' is not divided there; they get the fill value and are marked invalid (in " +
      (onPoints ? "vtkValidPointMask" : "vtkValidCellMask") + ", or in a mask of its own).");
}
} // namespace

void DivideByDensity(LeafContext& ctx, const OperatorSet& ops, const mp::SolverHooks hooks[2],
  LeafSolutions& solutions)
{
  for (Transfer t : AllTransfers)
  {
    const GatheredFields& g = ctx.Source.Fields[SourceAssociation(t)];
    if (!ops.Operators[t] || g.Components == 0 || !g.Mass.Active())
    {
      continue;
    }
    const mp::SolverHooks& hook = hooks[TargetSpaceOf(t) == mp::SpaceType::P1 ? 0 : 1];
    const size_t rows = solutions.Values[t].size() / static_cast<size_t>(g.Components);
    solutions.Products[t].assign(rows * static_cast<size_t>(ProductWidth(g)), 0.0);
    solutions.Guarded[t].assign(g.Mass.Weighted.size(), std::vector<char>());
    for (size_t w = 0; w < g.Mass.Weighted.size(); ++w)
    {
      double count = static_cast<double>(Divide(ctx, g, static_cast<int>(w), t, hook, solutions));
      ctx.Processes.Sum(&count, 1); // (collective: every process, every weighted array)
      WarnGuarded(ctx, g, g.Mass.Weighted[w], t, count);
    }
  }
}
} // namespace mpvtk
