// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/SourceFields.h"

#include "vtkDataArray.h"
#include "vtkDataArraySelection.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkIdList.h"
#include "vtkNew.h"

#include "Parallel/Parts.h"
#include "Projection/Fingerprint.h"
#include "Projection/Labels.h"
#include "Projection/Messages.h"
#include "Projection/Settings.h"
#include "Projection/TangentFields.h"
#include "Adapter/FieldArrays.h"
#include "Adapter/SimplexMesh.h"
#include "Adapter/Threads.h"

#include "Geometry/Measures.h"
#include "Mesh/ContentHash.h"
#include "Mesh/NodalCells.h"
#include "Transfer/Space.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>

namespace mpvtk
{
namespace
{
/// The enabled numeric fields of one association, long enough, in order
/// (labels apart; and `density`, hidden when not enabled, never a label).
void SelectArrays(vtkDataSet* source, int association, vtkDataArraySelection* selection,
  const Settings& settings, const std::string& density, Messages& messages, GatheredFields& g)
{
  vtkDataSetAttributes* data = AttributesOf(source, association);
  const char* kind = association == 0 ? "point" : "cell";
  const vtkIdType needed =
    association == 0 ? source->GetNumberOfPoints() : source->GetNumberOfCells();
  for (int i = 0; i < data->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* abstract = data->GetAbstractArray(i);
    const char* name = abstract->GetName();
    const std::string label = name ? name : "(unnamed)";
    const bool hidden = name && !selection->ArrayIsEnabled(name) && density == name;
    if (!IsField(data, abstract) || (name && !selection->ArrayIsEnabled(name) && !hidden))
    {
      continue;
    }
    vtkDataArray* array = vtkArrayDownCast<vtkDataArray>(abstract);
    if (array && array->GetNumberOfTuples() < needed)
    {
      messages.WarnOnce(std::string("short/") + kind + "/" + label,
        "Source " + std::string(kind) + " array '" + label + "' has " +
          std::to_string(array->GetNumberOfTuples()) + " tuples for " + std::to_string(needed) +
          " " + kind + "s: it is not projected (the dataset is inconsistent).");
      continue;
    }
    if (!array)
    {
      messages.Warn("Source " + std::string(kind) + " array '" + label + "' is not numeric (" +
        abstract->GetClassName() + "): skipped.");
      continue;
    }
    if (density != label && IsLabelArray(array, settings, association, &messages))
    {
      g.Labels.emplace_back();
      g.Labels.back().Array = array;
      continue;
    }
    if (HoldsIntegers(array))
    {
      messages.WarnOnce(std::string(kind) + "/" + label, // once per array, not per step
        "Source " + std::string(kind) + " array '" + label + "' holds integers (" +
          array->GetClassName() +
          "): it is projected as real values (a 0/1 indicator becomes a covered fraction, but "
          "labels and ids do not carry over: set CategoricalMode to CATEGORICAL_AUTOMATIC, or "
          "name it in CategoricalArrays, to project it as labels, or deselect it).");
    }
    g.AddArray(array, label, hidden);
  }
}

/// The arrays' values side by side, one row per kernel function.
void CopyValues(
  vtkDataSet* source, const SimplexMesh& mesh, int association, bool extensive, GatheredFields& g)
{
  const mp::Index n =
    association == 0 ? source->GetNumberOfPoints() : mp::SpaceSize(mp::SpaceType::P0, mesh.View());
  g.Values.resize(std::max<size_t>(static_cast<size_t>(n) * g.Components, 1));
  std::vector<double> measure;
  if (association == 1 && extensive)
  {
    measure = mp::ParentMeasures(mesh.View());
  }
  // P1 functions are the kernel's points (renumbered, maybe), P0 ones the dataset's cells.
  const bool points = association == 0;
  for (int a = 0, offset = 0; a < static_cast<int>(g.Arrays.size()); ++a)
  {
    vtkDataArray* array = g.Arrays[a];
    const int nc = array->GetNumberOfComponents();
    const int width = g.Components;
    mpvtk::For(0, n, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType f = begin; f < end; ++f)
      {
        // Extensive values become densities (total / measure).
        const double scale = measure.empty() ? 1.0 : (measure[f] > 0 ? 1.0 / measure[f] : 0.0);
        const vtkIdType from = points ? mesh.DataSetPoint(f) : f;
        for (int k = 0; k < nc; ++k)
        {
          g.Values[f * width + offset + k] = scale * array->GetComponent(from, k);
        }
      }
    });
    offset += nc;
  }
}

/// The kernel functions where a component of array a is NaN or infinite, and how many values.
std::vector<char> NonFiniteFunctions(
  const GatheredFields& g, int a, mp::Index functions, vtkIdType& values)
{
  const int nc = g.Arrays[a]->GetNumberOfComponents();
  const int offset = g.Offsets[a];
  const int width = g.Components;
  std::vector<char> bad(static_cast<size_t>(functions), 0);
  std::atomic<vtkIdType> count(0);
  mpvtk::For(0, functions, [&](vtkIdType begin, vtkIdType end) {
    vtkIdType here = 0;
    for (vtkIdType f = begin; f < end; ++f)
    {
      for (int k = 0; k < nc; ++k)
      {
        const bool finite = std::isfinite(g.Values[f * width + offset + k]);
        here += !finite;
        bad[f] = bad[f] || !finite;
      }
    }
    count += here;
  });
  values = count;
  return bad;
}

/// The Source cells (kernel simplices) that use a bad function.
std::vector<char> CellsUsing(
  const mp::MeshView& view, const std::vector<char>& bad, int association)
{
  std::vector<char> excluded(static_cast<size_t>(view.NumberOfCells), 0);
  mpvtk::For(0, view.NumberOfCells, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType c = begin; c < end; ++c)
    {
      if (association == 1)
      {
        excluded[c] = bad[view.ParentOf(c)];
        continue;
      }
      mp::ForEachFunctionPoint(view, c, [&](mp::Index p) { excluded[c] = excluded[c] || bad[p]; });
    }
  });
  return excluded;
}

/// A Source point's identity over the processes: its coordinates' bits (a
/// point on the border of two pieces is one point, whatever ids they gave it).
void PointIdentity(vtkDataSet* source, vtkIdType p, long long key[3])
{
  double x[3];
  source->GetPoint(p, x);
  std::memcpy(key, x, sizeof(x));
}

/// A Source cell's identity over the processes: its points' identities,
/// sorted and hashed, and their number.
void CellIdentity(vtkDataSet* source, vtkIdType c, vtkIdList* ids, long long key[3])
{
  source->GetCellPoints(c, ids);
  std::vector<std::array<long long, 3>> corners(static_cast<size_t>(ids->GetNumberOfIds()));
  for (size_t k = 0; k < corners.size(); ++k)
  {
    PointIdentity(source, ids->GetId(static_cast<vtkIdType>(k)), corners[k].data());
  }
  std::sort(corners.begin(), corners.end());
  key[0] = static_cast<long long>(
    mp::Fnv1a64(corners.data(), corners.size() * sizeof(std::array<long long, 3>)));
  key[1] = static_cast<long long>(corners.size());
  key[2] = 0;
}

/**
 * The sum over the processes of `counts` (entry i of this process, known
 * by the identity keys[3i .. 3i + 2]), each item counted once however many
 * copies the processes hold: every copy counts its share. (The processes'
 * gathered Sources overlap: a cell two parts of Input need is on both, and
 * without the Source's own GlobalIds a point on the border of two pieces
 * is twice on a process that gathers both.) Collective.
 */
vtkIdType CountedOnce(
  Parts& parts, const std::vector<long long>& keys, const std::vector<double>& counts)
{
  const std::vector<double> copies =
    parts.SumByKey(keys, 3, std::vector<double>(counts.size(), 1.0));
  double total = 0.0;
  for (size_t i = 0; i < counts.size(); ++i)
  {
    total += counts[i] / copies[i];
  }
  parts.Sum(&total, 1);
  return static_cast<vtkIdType>(std::llround(total));
}

/**
 * What the warning of array a says, over all processes on several: its
 * non-finite values (`values` comes in with this process's count, `bad`
 * its functions with one) and the Source cells left out, each point and
 * cell counted once (CountedOnce): the serial run's numbers over the
 * Source cells some process gathered (every cell near Input). Collective
 * on several processes; one process: `values` and the cells as they are.
 */
vtkIdType CountLeftOut(vtkDataSet* source, const SimplexMesh& mesh, const GatheredFields& g, int a,
  int association, const std::vector<char>& bad, const NaNGroup& group, Parts& parts,
  vtkIdType& values)
{
  const std::vector<char> parents = LeftOutCells(mesh.View(), group);
  if (parts.Whole())
  {
    return std::count(parents.begin(), parents.end(), 1);
  }
  vtkNew<vtkIdList> ids;
  std::vector<long long> keys;
  std::vector<double> counts;
  const int nc = g.Arrays[a]->GetNumberOfComponents();
  for (size_t f = 0; f < bad.size(); ++f)
  {
    if (!bad[f])
    {
      continue;
    }
    long long key[3];
    if (association == 0)
    {
      PointIdentity(source, mesh.DataSetPoint(static_cast<mp::Index>(f)), key);
    }
    else
    {
      CellIdentity(source, static_cast<vtkIdType>(f), ids, key);
    }
    keys.insert(keys.end(), key, key + 3);
    int here = 0;
    for (int k = 0; k < nc; ++k)
    {
      here += !std::isfinite(g.Values[f * g.Components + g.Offsets[a] + k]);
    }
    counts.push_back(here);
  }
  values = CountedOnce(parts, keys, counts);
  keys.clear();
  for (size_t c = 0; c < parents.size(); ++c)
  {
    if (parents[c])
    {
      long long key[3];
      CellIdentity(source, static_cast<vtkIdType>(c), ids, key);
      keys.insert(keys.end(), key, key + 3);
    }
  }
  return CountedOnce(parts, keys, std::vector<double>(keys.size() / 3, 1.0));
}

/// Says once per array how many values and cells are left out (not for an
/// array with a hole where pieces lack it: PieceArrays.h's warning said it).
void WarnNonFinite(const std::string& label, int association, vtkIdType values, vtkIdType cells,
  Messages& messages, bool hole)
{
  const char* kind = association == 0 ? "point" : "cell";
  const std::string key = std::string("nonfinite/") + kind + "/" + label;
  if (values == 0 || hole || !messages.First(key))
  {
    return;
  }
  messages.Warn("Source " + std::string(kind) + " array '" + label + "' has " +
    std::to_string(values) + " NaN or infinite values: the " + std::to_string(cells) +
    " Source cells that use them are left out of its projection, as a hole in Source (the "
    "integral over the rest of the covered part is conserved). Input points and cells left "
    "without data for it get the fill value and are marked invalid (in vtkValidPointMask and "
    "vtkValidCellMask, or in masks of its own when the arrays' masks differ).");
}

/// Each group's arrays side by side, non-finite values as 0 (never used:
/// their cells are out); their columns in Values likewise, for the
/// operator of the other arrays.
void SplitOffGroups(GatheredFields& g, mp::Index functions)
{
  const int width = g.Components;
  for (NaNGroup& group : g.Groups)
  {
    group.Values.assign(static_cast<size_t>(functions) * group.Components, 0.0);
    int column = 0;
    for (int a : group.Arrays)
    {
      const int nc = g.Arrays[a]->GetNumberOfComponents();
      const int offset = g.Offsets[a];
      for (mp::Index f = 0; f < functions; ++f)
      {
        for (int k = 0; k < nc; ++k)
        {
          double& v = g.Values[f * width + offset + k];
          group.Values[f * group.Components + column + k] = std::isfinite(v) ? v : 0.0;
          v = 0.0;
        }
      }
      column += nc;
    }
  }
}

/// The NaN groups of one association.
void FindNaNGroups(vtkDataSet* source, const SimplexMesh& mesh, int association, Messages& messages,
  Parts& parts, GatheredFields& g)
{
  const mp::MeshView& view = mesh.View();
  const mp::Index functions = static_cast<mp::Index>(g.Values.size() / std::max(g.Components, 1));
  for (int a = 0; a < static_cast<int>(g.Arrays.size()); ++a)
  {
    vtkIdType values = 0;
    const std::vector<char> bad = NonFiniteFunctions(g, a, functions, values);
    // An array with non-finite values on any process is projected with its
    // own operator on all (with no cell left out where it has none).
    std::vector<char> anywhere(1, values > 0);
    parts.Or(anywhere);
    if (!anywhere[0])
    {
      continue;
    }
    std::vector<char> excluded = CellsUsing(view, bad, association);
    Fingerprint print;
    print.Add(excluded.data(), excluded.size(), mpvtk::SMPTaskRunner());
    // One process: arrays leaving out the same cells share a group. Several:
    // each array a group of its own, alike on every process.
    auto group = !parts.Whole()
      ? g.Groups.end()
      : std::find_if(g.Groups.begin(), g.Groups.end(),
          [&](const NaNGroup& h) { return h.Print == print.Hash && h.Excluded == excluded; });
    if (group == g.Groups.end())
    {
      g.Groups.emplace_back();
      group = std::prev(g.Groups.end());
      group->Excluded.swap(excluded);
      group->Print = print.Hash;
    }
    group->Arrays.push_back(a);
    group->Components += g.Arrays[a]->GetNumberOfComponents();
    const std::string label = g.Arrays[a]->GetName() ? g.Arrays[a]->GetName() : "(unnamed)";
    // (The dataset's cells left out: a split cell counts once.)
    const vtkIdType cells =
      CountLeftOut(source, mesh, g, a, association, bad, *group, parts, values);
    WarnNonFinite(label, association, values, cells, messages, g.Holes.count(label) > 0);
  }
  SplitOffGroups(g, functions);
}
} // namespace

void GatheredFields::AddArray(vtkDataArray* array, const std::string& label, bool hidden)
{
  this->Arrays.push_back(array);
  this->Hidden.push_back(hidden);
  this->Offsets.push_back(this->Components);
  this->Components += array->GetNumberOfComponents();
  this->Key += label + "/" + std::to_string(array->GetNumberOfComponents()) + ";";
}

std::vector<char> LeftOutCells(const mp::MeshView& view, const NaNGroup& group)
{
  std::vector<char> parents(static_cast<size_t>(view.Parents()), 0);
  for (mp::Index c = 0; c < view.NumberOfCells; ++c)
  {
    parents[view.ParentOf(c)] |= group.Excluded[c];
  }
  return parents;
}

void GatherSourceFields(vtkDataSet* source, const SimplexMesh& mesh,
  vtkDataArraySelection* const selections[2], const Settings& settings, Messages& messages,
  Parts& parts, GatheredFields fields[2])
{
  const bool extensive = settings.Extensive;
  const int density = DensityAssociation(source, settings, messages);
  for (int association = 0; association < 2; ++association)
  {
    // Arrays that differ between Source's pieces or blocks (Adapter/PieceArrays.h).
    for (const auto& warning : fields[association].PieceWarnings)
    {
      if (selections[association]->ArrayIsEnabled(warning.first.c_str()))
      {
        messages.WarnOnce("pieces/" + warning.second, warning.second); // once, not at every step
      }
    }
    SelectArrays(source, association, selections[association], settings,
      association == density ? settings.DensityArray : std::string(), messages,
      fields[association]);
  }
  fields[1].Key += extensive ? "extensive" : "intensive";
  for (int association = 0; association < 2; ++association)
  {
    GatheredFields& g = fields[association];
    IndexLabels(mesh, association, settings.ReconstructsCellData(),
      settings.CategoricalMode == CategoricalAutomatic, parts, g);
    CheckLabelCounts(association, settings, messages, g);
    if (g.Components == 0)
    {
      continue;
    }
    CopyValues(source, mesh, association, extensive, g);
    WeighSourceFields(settings, association, density, source, parts, messages, g);
  }
  // (Before the NaN groups take their arrays' columns.)
  RemoveSourceNormalParts(source, mesh, settings, messages, parts, fields);
  for (int association = 0; association < 2; ++association)
  {
    GatheredFields& g = fields[association];
    if (g.Components > 0)
    {
      FindNaNGroups(source, mesh, association, messages, parts, g);
    }
  }
}
} // namespace mpvtk
