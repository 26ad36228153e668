// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Outputs.h"

#include "vtkAppendFilter.h"
#include "vtkAppendPolyData.h"
#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"

#include "Mesh/NodalCells.h"
#include "Projection/Conservation.h"
#include "Projection/Labels.h"
#include "Projection/Messages.h"
#include "Projection/Settings.h"
#include "Projection/SourceSide.h"
#include "Projection/TangentFields.h"
#include "Adapter/CompositeLeaves.h"
#include "Adapter/FieldArrays.h"
#include "Adapter/IntersectionOutput.h"
#include "Adapter/SimplexMesh.h"
#include "Adapter/Threads.h"

#include <algorithm>
#include <optional>
#include <deque>
#include <string>
#include <utility>

namespace mpvtk
{
namespace
{
/// Per array written: its name and where it is valid (in the dataset's numbering).
using Validity = std::vector<std::pair<std::string, const std::vector<char>*>>;

/// to[0..n) = from[0..n), in the filter's threads (each the first to touch
/// its part of a fresh output array).
template <class T>
void CopyInThreads(const T* from, size_t n, T* to)
{
  mpvtk::For(0, static_cast<vtkIdType>(n), 65536,
    [&](vtkIdType begin, vtkIdType end) { std::copy(from + begin, from + end, to + begin); });
}

/// P1 functions are the kernel's points: flags per function in the
/// dataset's point numbering when the target was renumbered (copies kept
/// while the outputs are written).
class PointNumbering
{
public:
  explicit PointNumbering(const SimplexMesh& target)
    : Target(target)
  {}
  const std::vector<char>* InDataSet(const std::vector<char>& valid)
  {
    if (!this->Target.Ordered())
    {
      return &valid;
    }
    this->Copies.emplace_back(valid.size());
    std::vector<char>& copy = this->Copies.back();
    mpvtk::For(0, static_cast<vtkIdType>(valid.size()), [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType f = begin; f < end; ++f)
      {
        copy[static_cast<size_t>(this->Target.DataSetPoint(f))] = valid[f];
      }
    });
    return &copy;
  }

private:
  const SimplexMesh& Target;
  std::deque<std::vector<char>> Copies;
};

/// What the arrays of one leaf write, for the masks and active scalars.
struct Written
{
  std::vector<std::string> PointNames, CellNames; // by the transfers to the fields' own association
  Validity PointValid, CellValid;
  /// Validities of mass-weighted arrays that the density guard narrowed (MassWeighting.h).
  std::deque<std::vector<char>> Narrowed;
};

/// Where array a of transfer t is valid: its system's functions, less those the density guard left.
const std::vector<char>* ValidOf(
  const GatheredFields& g, int a, Transfer t, const LeafSolutions& solutions, Written& written)
{
  const std::vector<char>* valid = solutions.ByArray[t][static_cast<size_t>(a)].Valid;
  const int w = g.Mass.Active() ? g.Mass.WeightedIndex(a) : -1;
  if (w < 0 || solutions.Guarded[t][static_cast<size_t>(w)].empty())
  {
    return valid;
  }
  const std::vector<char>& guarded = solutions.Guarded[t][static_cast<size_t>(w)];
  written.Narrowed.emplace_back(*valid);
  std::vector<char>& narrowed = written.Narrowed.back();
  for (size_t f = 0; f < narrowed.size(); ++f)
  {
    narrowed[f] = narrowed[f] && !guarded[f];
  }
  return &narrowed;
}

/// The name of array a of transfer t in the output (renamed when it clashes).
std::string OutputName(
  vtkDataArray* array, int a, Transfer t, const std::vector<std::string>& written)
{
  const bool fromCells = SourceAssociation(t) == 1;
  std::string name = array->GetName()
    ? array->GetName()
    : (fromCells ? "ProjectedCellArray" : "ProjectedArray") + std::to_string(a);
  if (!IsOwnAssociation(t) && std::find(written.begin(), written.end(), name) != written.end())
  {
    name += fromCells ? " (from cells)" : " (from points)";
  }
  return name;
}

/// SourceIntegral_ and TargetIntegral_ of one array (a trace has no Source integral).
void WriteIntegrals(vtkFieldData* data, const std::string& name, bool fromCells, bool trace,
  const ArrayIntegrals& integrals, int nc)
{
  for (int which = trace ? 1 : 0; which < 2; ++which)
  {
    vtkNew<vtkDoubleArray> integral;
    integral->SetName(
      ((which ? "TargetIntegral_" : "SourceIntegral_") + name + (fromCells ? " (cell data)" : ""))
        .c_str());
    integral->SetNumberOfComponents(nc);
    integral->SetNumberOfTuples(1);
    for (int k = 0; k < nc; ++k)
    {
      integral->SetComponent(0, k, which ? integrals.Target[k] : integrals.Source[k]);
    }
    data->AddArray(integral);
  }
}

/// Where the Source values of array a are: its NaN group's block, or the gathered one.
struct SourceColumns
{
  const FieldBlock* Block;
  int Width;
  int Offset;
};

SourceColumns SourceColumnsOf(const GatheredFields& g, int a)
{
  for (const NaNGroup& group : g.Groups)
  {
    int column = 0;
    for (int member : group.Arrays)
    {
      if (member == a)
      {
        return { &group, group.Components, column };
      }
      column += g.Arrays[member]->GetNumberOfComponents();
    }
  }
  return { &g, g.Components, g.Offsets[a] };
}

/**
 * A tangent array's normal part at the target removed from `out` (written
 * in the dataset's numbering) where it is valid or extrapolated, and its
 * magnitude written as "<name>_NormalPart" (the fill value elsewhere); a
 * warning when it is large (LargeNormalPart) next to the field (not on a
 * trace, whose vectors are a volume's), or when the target is neither
 * surface nor curve (the array is left as projected).
 */
void WriteTangentPart(LeafContext& ctx, TargetTangents& tangents, vtkDoubleArray* out, Transfer t,
  const std::vector<char>& valid, const LeafSolutions& solutions, vtkDataSetAttributes* outData)
{
  const std::string name = out->GetName();
  if (!tangents.Applies())
  {
    ctx.Say.WarnOnce("tangent/ignored/" + name,
      "TangentArrays: '" + name + "' is not made tangent on " + ctx.Role + ", whose cells are " +
        std::to_string(tangents.CellDimension()) +
        "D (only surfaces and curves have a tangent plane): it is projected as an ordinary "
        "array.");
    return;
  }
  const bool toPoints = ToPoints(t);
  const vtkIdType n = out->GetNumberOfTuples();
  std::vector<char> keep(valid.begin(), valid.begin() + n);
  const std::vector<char>& extrapolated = solutions.Extrapolated[t];
  for (size_t f = 0; f < extrapolated.size(); ++f)
  {
    const vtkIdType at =
      toPoints ? ctx.Target.DataSetPoint(static_cast<mp::Index>(f)) : static_cast<vtkIdType>(f);
    keep[at] = keep[at] || extrapolated[f];
  }
  double largest[2] = { 0.0, 0.0 }; // removed, field
  const std::vector<double> removed = tangents.Remove(
    out->GetPointer(0), n, toPoints, keep, ctx.Options.Fill(), largest[0], largest[1]);
  vtkNew<vtkDoubleArray> part;
  part->SetName((name + "_NormalPart").c_str());
  part->SetNumberOfValues(n);
  std::copy(removed.begin(), removed.end(), part->GetPointer(0));
  outData->AddArray(part);
  ctx.Processes.Maximum(largest, 2);
  // (A trace's vectors are the volume's: their normal part is no surprise.)
  if (largest[0] > LargeNormalPart * largest[1] && !ctx.Shape.Trace)
  {
    ctx.Say.WarnOnce("tangent/large/" + ctx.Role + "/" + name,
      "TangentArrays: the projected '" + name + "' on " + ctx.Role + " had a normal part up to " +
        std::to_string(largest[0]) + " (removed, see " + name +
        "_NormalPart) for a largest magnitude of " + std::to_string(largest[1]) +
        ": the meshes' normals differ much there (a coarse facetization, or Input off Source).");
  }
}

/**
 * ConserveSourceIntegral's scale of each component of array a: its
 * integrals' Factor, and for a mass-weighted array that divided by the
 * density's own (the density is written scaled), so that the written
 * density times the written q keeps the Source's integral of rho q and a
 * constant q stays constant. Collective (the density's weights and sums):
 * the density's own scale is integrated once per transfer, by its first
 * weighted array on every process, and kept in `densityScale`.
 */
std::vector<double> ValueFactors(LeafContext& ctx, const OperatorSet& ops,
  const LeafSolutions& solutions, SourceWeights& weights, Transfer t, int a,
  const ArrayIntegrals& integrals, std::optional<double>& densityScale)
{
  const GatheredFields& g = ctx.Source.Fields[SourceAssociation(t)];
  std::vector<double> factors = integrals.Factor;
  const bool conserve = ctx.Options.ConserveSourceIntegral && !ctx.Shape.Trace;
  if (!conserve || !g.Mass.Active() || g.Mass.WeightedIndex(a) < 0)
  {
    return factors;
  }
  if (!densityScale)
  {
    const int d = g.Mass.Density;
    const SourceColumns source = SourceColumnsOf(g, d);
    const vtkIdType n =
      ToPoints(t) ? ctx.TargetData->GetNumberOfPoints() : ctx.TargetData->GetNumberOfCells();
    const ProjectedArray density{ solutions.ByArray[t][static_cast<size_t>(d)],
      weights.Of(*ops.ByArray[t][d]), source.Block->Functions(), source.Width, source.Offset,
      solutions.Values[t], g.Components, g.Offsets[d], 1, n };
    densityScale =
      Integrate(density, true, ctx.Options.DensityArray, ctx.Role, ctx.Processes, ctx.Say)
        .Factor[0];
  }
  for (double& factor : factors)
  {
    factor /= *densityScale;
  }
  return factors;
}

/// The arrays of transfer t (with their integrals for the fields' own association).
void WriteTransfer(LeafContext& ctx, vtkDataSet* output, const OperatorSet& ops,
  const LeafSolutions& solutions, SourceWeights& weights, Transfer t, PointNumbering& numbering,
  TargetTangents& tangents, Written& written)
{
  const GatheredFields& g = ctx.Source.Fields[SourceAssociation(t)];
  const bool toPoints = ToPoints(t);
  const bool fromCells = SourceAssociation(t) == 1;
  const bool trace = ctx.Shape.Trace;
  // Densities back to totals; on a trace they stay the Source's densities
  // (per unit of its volume or area: a surface holds no part of a total).
  const bool totals = t == CellsToCells && ctx.Options.Extensive && !trace;
  vtkDataSetAttributes* sourceData = AttributesOf(ctx.Source.Data, SourceAssociation(t));
  vtkDataSetAttributes* outData = AttributesOf(output, toPoints ? PointArrays : CellArrays);
  std::vector<std::string>& names = toPoints ? written.PointNames : written.CellNames;
  const vtkIdType n =
    toPoints ? ctx.TargetData->GetNumberOfPoints() : ctx.TargetData->GetNumberOfCells();
  const mp::LargeVector<double>& values = solutions.Values[t];
  std::optional<double> densityScale; // (ValueFactors: once per transfer)
  for (int a = 0, offset = 0; a < static_cast<int>(g.Arrays.size()); ++a)
  {
    vtkDataArray* array = g.Arrays[a];
    const int nc = array->GetNumberOfComponents();
    const mp::MortarOperator& op = *ops.ByArray[t][a];
    if (g.Hidden[a])
    {
      offset += nc;
      continue; // a density gathered for the mass weighting only
    }
    const std::string name = OutputName(array, a, t, names);
    names.push_back(name);
    const mp::ProjectedSystem& system = solutions.ByArray[t][static_cast<size_t>(a)];
    const std::vector<char>& valid = *ValidOf(g, a, t, solutions, written);
    (toPoints ? written.PointValid : written.CellValid)
      .emplace_back(name, toPoints ? numbering.InDataSet(valid) : &valid);
    const SourceColumns source = SourceColumnsOf(g, a);
    // A mass-weighted array's integrals are those of rho q, its projected product.
    const int w = g.Mass.Active() ? g.Mass.WeightedIndex(a) : -1;
    const bool product = w >= 0;
    const ProjectedArray projected{ system, weights.Of(op), source.Block->Functions(), source.Width,
      source.Offset, product ? solutions.Products[t] : values,
      product ? ProductWidth(g) : g.Components, product ? ProductOffset(g, w) : offset, nc, n };
    const ArrayIntegrals integrals = Integrate(projected,
      ctx.Options.ConserveSourceIntegral && !trace, name, ctx.Role, ctx.Processes, ctx.Say);
    const std::vector<double> factors =
      ValueFactors(ctx, ops, solutions, weights, t, a, integrals, densityScale);
    vtkNew<vtkDoubleArray> out;
    out->SetName(name.c_str());
    out->SetNumberOfComponents(nc);
    for (int k = 0; k < nc; ++k)
    {
      if (array->GetComponentName(k))
      {
        out->SetComponentName(k, array->GetComponentName(k));
      }
    }
    out->SetNumberOfTuples(n);
    double* to = out->GetPointer(0);
    const std::vector<double>& covered = *system.CoveredIntegrals;
    const double fill = ctx.Options.Fill();
    const int width = g.Components;
    const SimplexMesh& target = ctx.Target;
    mpvtk::For(0, n, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType f = begin; f < end; ++f)
      {
        const double scale = totals && valid[f] ? covered[f] : 1.0;
        const vtkIdType at = toPoints ? target.DataSetPoint(f) : f;
        for (int k = 0; k < nc; ++k)
        {
          to[at * nc + k] = !valid[f] && (*system.Valid)[f]
            ? fill // (left by the density guard: MassWeighting.h)
            : scale * (valid[f] ? factors[k] : 1.0) * values[f * width + offset + k];
        }
      }
    });
    if (nc == 3 && IsTangentArray(ctx.Options, array))
    {
      const std::vector<char>& where = toPoints ? *numbering.InDataSet(valid) : valid;
      WriteTangentPart(ctx, tangents, out, t, where, solutions, outData);
    }
    // (The transfers to the other association have the same integrals.)
    if (IsOwnAssociation(t))
    {
      WriteIntegrals(output->GetFieldData(), name, fromCells, trace, integrals, nc);
    }
    offset += nc;
    outData->AddArray(out);
    if (IsOwnAssociation(t) && array == sourceData->GetScalars())
    {
      outData->SetActiveScalars(out->GetName());
    }
    else if (IsOwnAssociation(t) && array == sourceData->GetVectors())
    {
      outData->SetActiveVectors(out->GetName());
    }
  }
}

/// The label arrays of transfer t (Labels.h), after its numbers: valid where
/// the transfer's numbers are (its operator's system), in the masks' list.
void WriteLabels(LeafContext& ctx, vtkDataSet* output, const LeafSolutions& solutions, Transfer t,
  PointNumbering& numbering, Written& written)
{
  const GatheredFields& g = ctx.Source.Fields[SourceAssociation(t)];
  const bool toPoints = ToPoints(t);
  vtkDataSetAttributes* sourceData = AttributesOf(ctx.Source.Data, SourceAssociation(t));
  vtkDataSetAttributes* outData = AttributesOf(output, toPoints ? PointArrays : CellArrays);
  std::vector<std::string>& names = toPoints ? written.PointNames : written.CellNames;
  const vtkIdType n =
    toPoints ? ctx.TargetData->GetNumberOfPoints() : ctx.TargetData->GetNumberOfCells();
  const SimplexMesh& target = ctx.Target;
  const std::function<vtkIdType(vtkIdType)> at = [&target, toPoints](vtkIdType f) {
    return toPoints ? target.DataSetPoint(f) : f;
  };
  const std::vector<char>& valid = *solutions.System[t].Valid;
  static const LabelSolution none;
  for (size_t i = 0; i < g.Labels.size(); ++i)
  {
    const LabelField& field = g.Labels[i];
    const std::string name =
      OutputName(field.Array, static_cast<int>(g.Arrays.size() + i), t, names);
    names.push_back(name);
    (toPoints ? written.PointValid : written.CellValid)
      .emplace_back(name, toPoints ? numbering.InDataSet(valid) : &valid);
    const LabelSolution& solution = i < solutions.Labels[t].size() ? solutions.Labels[t][i] : none;
    const LabelOutput out = WriteLabelArray(field, solution, valid, n, at, name, ctx.Options);
    outData->AddArray(out.Labels);
    if (out.Fractions)
    {
      outData->AddArray(out.Fractions);
    }
    if (IsOwnAssociation(t) && field.Array == sourceData->GetScalars())
    {
      outData->SetActiveScalars(out.Labels->GetName());
    }
  }
}

/// Without active scalars (none in Source, none in Input), the first
/// projected scalar array becomes them (points first), so that ParaView
/// shows the result coloured by it rather than in a solid colour.
void MakeActiveScalars(vtkDataSet* output, const Written& written)
{
  auto make = [](vtkDataSetAttributes* data, const std::vector<std::string>& names) {
    for (const std::string& name : names)
    {
      vtkDataArray* a = data->GetArray(name.c_str());
      if (a && a->GetNumberOfComponents() == 1)
      {
        data->SetActiveScalars(name.c_str());
        return true;
      }
    }
    return false;
  };
  vtkPointData* pd = output->GetPointData();
  vtkCellData* cd = output->GetCellData();
  if (!pd->GetScalars() && !cd->GetScalars() && !make(pd, written.PointNames))
  {
    make(cd, written.CellNames);
  }
}

/**
 * Adds `mask` (where the meshes overlap) to `data`. When arrays with
 * non-finite values are valid elsewhere: if every array written has the
 * same validity, `mask` becomes it; else each array valid elsewhere gets a
 * mask of its own, "<mask>_<array>".
 */
void AddValidMasks(vtkCharArray* mask, const Validity& arrays, vtkDataSetAttributes* data)
{
  const char* m = mask->GetPointer(0);
  const vtkIdType n = mask->GetNumberOfValues();
  auto same = [n](const char* a, const char* b) { return std::equal(a, a + n, b); };
  bool agree = !arrays.empty();
  for (const auto& a : arrays)
  {
    agree = agree && *a.second == *arrays[0].second;
  }
  if (agree && !same(arrays[0].second->data(), m))
  {
    std::copy(arrays[0].second->begin(), arrays[0].second->end(), mask->GetPointer(0));
  }
  else if (!agree)
  {
    for (const auto& a : arrays)
    {
      if (!same(a.second->data(), m))
      {
        vtkNew<vtkCharArray> own;
        own->SetName((std::string(mask->GetName()) + "_" + a.first).c_str());
        own->SetNumberOfValues(n);
        std::copy(a.second->begin(), a.second->end(), own->GetPointer(0));
        data->AddArray(own);
      }
    }
  }
  data->AddArray(mask);
}

/**
 * Valid points whose cells are all covered only in slivers and that the
 * fringe's aggregation left free: their values are extrapolated from a
 * sliver (an ill-conditioned row) and can be far off. Only with the
 * fringe off (FringeThreshold 0, or below the few percent such a point's
 * support is covered at most): with it on, such a point is aggregated or,
 * with no stencil, dropped (FringeStrandedDropFraction), on volumes,
 * surfaces, curves and traces alike. On several processes a
 * point on a partition boundary has cells on
 * each: it is such a point only when the cells of every process around it
 * are slivers (the hooks complete the cover across processes; alone they
 * do nothing). Counted once (by its owner), the total said once (by
 * process 0), as one process would.
 */
void WarnSliverPoints(LeafContext& ctx, const mp::MortarOperator& onPoints,
  const std::vector<char>& valid, const mp::LargeVector<double>& most,
  const mp::SolverHooks& shared)
{
  const size_t rows = static_cast<size_t>(ctx.TargetData->GetNumberOfPoints());
  mp::UninitializedLargeVector<double> covered(std::max(most.size(), rows));
  mpvtk::For(0, static_cast<vtkIdType>(covered.size()), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      covered[i] = static_cast<size_t>(i) < most.size() && most[i] >= 1e-3 ? 1.0 : 0.0;
    }
  });
  if (shared.Exchange)
  {
    shared.Exchange(covered.data(), 1);
  }
  const std::vector<char>& fringe = onPoints.GetFringe().Aggregated;
  // (A count: the same in any order.)
  double total = mpvtk::SMPTaskRunner().ForRanges(
    static_cast<mp::Index>(most.size()), [&](mp::Index begin, mp::Index end) {
      double count = 0.0;
      for (mp::Index i = begin; i < end; ++i)
      {
        const bool counted = !shared.Counted || static_cast<size_t>(i) >= rows || shared.Counted[i];
        // (An aggregated point's value is the extension of well-covered ones.)
        const bool aggregated = !fringe.empty() && fringe[i];
        count += valid[i] && !aggregated && covered[i] == 0.0 && counted ? 1.0 : 0.0;
      }
      return count;
    });
  ctx.Processes.Sum(&total, 1);
  total = ctx.Processes.Rank() == 0 ? total : 0.0;
  const vtkIdType slivers = static_cast<vtkIdType>(total);
  if (slivers > 0)
  {
    ctx.Say.WarnOnce("slivers/" + ctx.Role,
      std::to_string(slivers) + " " + ctx.Role +
        " points are valid through slivers only (every cell around them is covered less than "
        "0.1%): their values are extrapolated from the sliver and can be far off. Where Input "
        "reaches beyond Source, keep FringeThreshold at its default, or leave out "
        "points whose cells' CoveredFraction is that small.");
  }
}

/// vtkValidPointMask, vtkValidCellMask (when arrays go to cells) and CoveredFraction.
void WriteMasks(LeafContext& ctx, vtkDataSet* output, const OperatorSet& ops,
  const LeafSolutions& solutions, const mp::LargeVector<double>& most,
  const mp::SolverHooks& pointHooks, PointNumbering& numbering, const Written& written)
{
  const vtkIdType nt = ctx.TargetData->GetNumberOfPoints();
  const vtkIdType ntc = ctx.TargetData->GetNumberOfCells();
  vtkNew<vtkCharArray> mask;
  mask->SetName("vtkValidPointMask");
  mask->SetNumberOfValues(nt);
  // The mask of the points' own transfer, else of the cells' transfer to points.
  const Transfer toPoints = ops.Operators[PointsToPoints] ? PointsToPoints : CellsToPoints;
  const mp::MortarOperator* onPoints = ops.Operators[toPoints];
  if (onPoints)
  {
    const std::vector<char>& pointsValid = *solutions.System[toPoints].Valid;
    const std::vector<char>& valid = *numbering.InDataSet(pointsValid);
    CopyInThreads(valid.data(), valid.size(), mask->GetPointer(0));
    WarnSliverPoints(ctx, *onPoints, pointsValid, most, pointHooks);
  }
  else
  {
    // A point is valid when a cell around it meets the source.
    char* to = mask->GetPointer(0);
    const SimplexMesh& target = ctx.Target;
    mpvtk::For(0, static_cast<vtkIdType>(most.size()), [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType i = begin; i < end; ++i)
      {
        to[target.DataSetPoint(i)] = most[i] > 0 ? 1 : 0;
      }
    });
  }
  AddValidMasks(mask, written.PointValid, output->GetPointData());
  const Transfer toCells = ops.Operators[PointsToCells] ? PointsToCells : CellsToCells;
  if (ops.Operators[toCells])
  {
    const std::vector<char>& cellsValid = *solutions.System[toCells].Valid;
    vtkNew<vtkCharArray> cellMask;
    cellMask->SetName("vtkValidCellMask");
    cellMask->SetNumberOfValues(ntc);
    CopyInThreads(cellsValid.data(), cellsValid.size(), cellMask->GetPointer(0));
    AddValidMasks(cellMask, written.CellValid, output->GetCellData());
  }
  const mp::LargeVector<double>& fraction = ops.First()->GetCoveredFraction();
  vtkNew<vtkDoubleArray> covered;
  covered->SetName("CoveredFraction");
  covered->SetNumberOfValues(ntc);
  CopyInThreads(fraction.data(), fraction.size(), covered->GetPointer(0));
  output->GetCellData()->AddArray(covered);
}
/**
 * vtkExtrapolatedPointMask and vtkExtrapolatedCellMask (with Extrapolation):
 * where the masks' operators (those of vtkValidPointMask and
 * vtkValidCellMask) had their values extrapolated.
 */
void WriteExtrapolatedMasks(
  LeafContext& ctx, vtkDataSet* output, const OperatorSet& ops, const LeafSolutions& solutions)
{
  if (ctx.Options.Extrapolation == mp::ExtrapolationMode::None)
  {
    return;
  }
  const Transfer toPoints = ops.Operators[PointsToPoints] ? PointsToPoints : CellsToPoints;
  const Transfer toCells = ops.Operators[PointsToCells] ? PointsToCells : CellsToCells;
  for (const Transfer t : { toPoints, toCells })
  {
    const std::vector<char>& from = solutions.Extrapolated[t];
    if (!ops.Operators[t] || from.empty())
    {
      continue;
    }
    const bool points = t == toPoints;
    vtkNew<vtkCharArray> mask;
    mask->SetName(points ? "vtkExtrapolatedPointMask" : "vtkExtrapolatedCellMask");
    mask->SetNumberOfValues(
      points ? ctx.TargetData->GetNumberOfPoints() : ctx.TargetData->GetNumberOfCells());
    mask->FillValue(0);
    for (size_t f = 0; f < from.size(); ++f)
    {
      mask->SetValue(
        points ? ctx.Target.DataSetPoint(static_cast<mp::Index>(f)) : static_cast<vtkIdType>(f),
        from[f]);
    }
    (points ? static_cast<vtkDataSetAttributes*>(output->GetPointData())
            : static_cast<vtkDataSetAttributes*>(output->GetCellData()))
      ->AddArray(mask);
  }
}
} // namespace

void PassInput(vtkDataObject* input, vtkDataObject* output, vtkPolyData* polygons,
  vtkUnstructuredGrid* polyhedra)
{
  vtkCompositeDataSet* composite = vtkCompositeDataSet::SafeDownCast(input);
  if (composite)
  {
    // Each leaf its own shallow copy: the arrays are added to the copies, not to Input.
    vtkCompositeDataSet* out = vtkCompositeDataSet::SafeDownCast(output);
    out->CopyStructure(composite);
    ForEachLeaf(composite, [&](vtkCompositeDataIterator* at) {
      vtkDataObject* leaf = at->GetCurrentDataObject();
      vtkSmartPointer<vtkDataObject> copy;
      copy.TakeReference(leaf->NewInstance());
      copy->ShallowCopy(leaf);
      out->SetDataSet(at, copy);
    });
  }
  else
  {
    output->ShallowCopy(input);
  }
  polygons->Initialize();
  polyhedra->Initialize();
}

mp::LargeVector<double> PointCover(const SimplexMesh& target, OperatorSet& ops)
{
  const mp::MeshView& view = target.View();
  mp::LargeVector<double> most;
  // Made with M_tt (P1 target functions of an operator built here), in
  // the filter's threads; else here.
  for (std::unique_ptr<mp::MortarOperator>& fresh : ops.Fresh)
  {
    if (fresh && fresh.get() == ops.First())
    {
      fresh->TakePointCover(most);
    }
  }
  if (most.size() == static_cast<size_t>(view.NumberOfPoints))
  {
    return most;
  }
  const mp::LargeVector<double>& fraction = ops.First()->GetCoveredFraction();
  most.assign(static_cast<size_t>(view.NumberOfPoints), 0.0);
  for (mp::Index c = 0; c < view.NumberOfCells; ++c)
  {
    const double f = fraction[static_cast<size_t>(view.ParentOf(c))];
    mp::ForEachFunctionPoint(view, c, [&](mp::Index p) {
      most[static_cast<size_t>(p)] = std::max(most[static_cast<size_t>(p)], f);
    });
  }
  return most;
}

void WriteLeafOutputs(LeafContext& ctx, vtkDataSet* output, const OperatorSet& ops,
  const LeafSolutions& solutions, SourceWeights& weights, const mp::LargeVector<double>& pointCover,
  const mp::SolverHooks& pointHooks)
{
  PointNumbering numbering(ctx.Target);
  Written written;
  TargetTangents tangents(
    ctx.TargetData, ctx.Target, pointHooks, static_cast<vtkIdType>(pointCover.size()));
  for (Transfer t : OutputOrder)
  {
    if (ops.Operators[t] && ctx.Source.Fields[SourceAssociation(t)].Components > 0)
    {
      WriteTransfer(ctx, output, ops, solutions, weights, t, numbering, tangents, written);
    }
    if (ops.Operators[t])
    {
      WriteLabels(ctx, output, solutions, t, numbering, written);
    }
  }
  MakeActiveScalars(output, written);
  WriteMasks(ctx, output, ops, solutions, pointCover, pointHooks, numbering, written);
  WriteExtrapolatedMasks(ctx, output, ops, solutions);
}

vtkSmartPointer<vtkDataObject> LeafPieces(const LeafContext& ctx, const OperatorSet& ops)
{
  const mp::IntersectionPieces& pieces = ops.First()->GetPieces();
  switch (ctx.Target.Dimension())
  {
    case 1:
      return mpvtk::MakeIntersectionSegments(pieces, ctx.Target, ctx.Source.Mesh);
    case 2:
      return mpvtk::MakeIntersectionPolygons(pieces, ctx.Target, ctx.Source.Mesh);
    default:
      return mpvtk::MakeIntersectionPolyhedra(pieces, ctx.Target, ctx.Source.Mesh);
  }
}

void WritePieces(const std::vector<vtkSmartPointer<vtkDataObject>>& pieces, vtkPolyData* polygons,
  vtkUnstructuredGrid* polyhedra)
{
  if (pieces.size() == 1)
  {
    (vtkPolyData::SafeDownCast(pieces[0]) ? static_cast<vtkDataObject*>(polygons) : polyhedra)
      ->ShallowCopy(pieces[0]);
    return;
  }
  vtkNew<vtkAppendPolyData> appendPolygons;
  vtkNew<vtkAppendFilter> appendPolyhedra;
  for (const auto& p : pieces)
  {
    if (vtkPolyData* poly = vtkPolyData::SafeDownCast(p))
    {
      appendPolygons->AddInputData(poly);
    }
    else
    {
      appendPolyhedra->AddInputData(vtkDataSet::SafeDownCast(p));
    }
  }
  if (appendPolygons->GetNumberOfInputConnections(0) > 0)
  {
    appendPolygons->Update();
    polygons->ShallowCopy(appendPolygons->GetOutput());
  }
  if (appendPolyhedra->GetNumberOfInputConnections(0) > 0)
  {
    appendPolyhedra->Update();
    polyhedra->ShallowCopy(appendPolyhedra->GetOutput());
  }
}
} // namespace mpvtk
