// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Conservation.h"

#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkPointData.h"

#include "Parallel/Parts.h"
#include "Projection/Messages.h"
#include "Adapter/SimplexMesh.h"
#include "Adapter/Threads.h"

#include "Geometry/Measures.h"
#include "Mesh/BlockSums.h"
#include "Mesh/CellCornersInOrder.h"
#include "Transfer/NodalSpace.h"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <sstream>

namespace mpvtk
{
/**
 * On several processes each has its part of a source cell's covered
 * measure (the pieces of its own target cells): for the 90% rule, which is
 * not linear, the parts of surfaces' and curves' cells are summed over the
 * processes (by the cells' corners' global ids) and each process takes its
 * share of the result. (Otherwise the measures are only capped at the
 * cell's own, which parts that do not overlap never reach.) A collective:
 * called for every array on every process; `needed` false (the weights
 * known) sends nothing.
 */
std::vector<double> SourceWeights::CoveredTotals(const mp::MortarOperator& op, bool needed)
{
  std::vector<double> total;
  if (this->Processes.Whole())
  {
    return total; // one process: each cell's cover is whole here
  }
  const mp::MeshView& view = this->Source.View();
  // (Volumes and planar meshes have no such rule: no keys, but the call is
  // collective all the same: a process's meshes may be empty.)
  const bool projected = view.IsSurfaceMesh() || view.IsCurveMesh();
  const int corners = view.CornersPerCell();
  const mp::LargeVector<double>& covered = op.GetSourceCovered();
  std::vector<long long> keys;
  std::vector<double> parts;
  std::vector<mp::Index> cells;
  vtkDataArray* global = this->SourceData->GetPointData()->GetGlobalIds();
  if (needed && projected && global && corners <= 3)
  {
    for (mp::Index c = 0; c < view.NumberOfCells; ++c)
    {
      if (covered[static_cast<size_t>(c)] > 0.0)
      {
        // The corners' global ids, sorted, and the parity of that sort:
        // a cell is the same on every process, and two cells on the same
        // corners in opposite orientations (a curve going back along
        // itself, a two-sided surface) stay apart.
        long long key[4] = { -1, -1, -1, 0 };
        for (int k = 0; k < corners; ++k)
        {
          const mp::Index p = view.Cell(c)[k];
          // A geometric-only point (a curved cell split finer) has no global
          // id: its coordinates' bits, the same on every process, name it.
          unsigned long long bits = 0;
          if (!view.HasFunction(p))
          {
            for (int d = 0; d < 3; ++d)
            {
              unsigned long long w = 0;
              std::memcpy(&w, view.Point(p) + d, sizeof w);
              bits = bits * 1000003ULL ^ w;
            }
          }
          key[k] = view.HasFunction(p)
            ? static_cast<long long>(global->GetTuple1(this->Source.DataSetPoint(p)))
            : static_cast<long long>((bits >> 2) | (1ULL << 62));
        }
        for (int k = 0; k < corners; ++k)
        {
          for (int j = k + 1; j < corners; ++j)
          {
            key[3] ^= key[k] > key[j] ? 1 : 0;
          }
        }
        std::sort(key, key + corners);
        keys.insert(keys.end(), key, key + 4);
        parts.push_back(covered[static_cast<size_t>(c)]);
        cells.push_back(c);
      }
    }
  }
  const std::vector<double> sums = this->Processes.SumByKey(keys, 4, parts);
  if (!cells.empty())
  {
    total.assign(static_cast<size_t>(view.NumberOfCells), 0.0);
    for (size_t i = 0; i < cells.size(); ++i)
    {
      total[static_cast<size_t>(cells[i])] = sums[i];
    }
  }
  return total;
}

const std::vector<double>& SourceWeights::Make(
  const mp::MortarOperator& op, const std::vector<double>& total)
{
  std::vector<double>& w = this->Weights[&op];
  const mp::MeshView& view = this->Source.View();
  const mp::SpaceType space = op.GetSourceSpace();
  if (w.empty())
  {
    w.assign(static_cast<size_t>(mp::SpaceSize(space, view)), 0.0);
    const int corners = view.CornersPerCell();
    const mp::LargeVector<double>& covered = op.GetSourceCovered();
    const bool projected = view.IsSurfaceMesh() || view.IsCurveMesh();
    // The cells' measures in the filter's threads (0: degenerate), then
    // summed in cell order.
    mp::UninitializedLargeVector<double> measures(static_cast<size_t>(view.NumberOfCells));
    mpvtk::For(0, view.NumberOfCells, [&](vtkIdType begin, vtkIdType end) {
      std::fill(measures.begin() + begin, measures.begin() + end, 0.0);
      mp::ForEachCellMeasure(
        view, [&](mp::Index c, double whole) { measures[static_cast<size_t>(c)] = whole; }, begin,
        end);
    });
    // The part of cell c counted (0: none).
    auto part = [&](mp::Index c) {
      const double whole = measures[static_cast<size_t>(c)];
      const double m = covered[static_cast<size_t>(c)];
      if (!(whole > 0.0) || !(m > 0.0))
      {
        return 0.0;
      }
      // The rule: a cell covered to 90% counts whole (surfaces, curves).
      auto counted = [&](double cover) {
        return projected && cover >= 0.9 * whole ? whole : std::min(cover, whole);
      };
      // With the processes' total cover `all`: this process's share of it.
      const double all = total.empty() ? 0.0 : total[static_cast<size_t>(c)];
      return all > 0.0 ? m * (counted(all) / all) : counted(m);
    };
    if (space == mp::SpaceType::DP1)
    {
      // Each function's own covered integral, in the share the rule counts
      // of its simplex's cover.
      const mp::LargeVector<double>& integrals = op.GetSourceFunctionCovered();
      mpvtk::For(0, view.NumberOfCells, [&](vtkIdType begin, vtkIdType end) {
        for (vtkIdType c = begin; c < end; ++c)
        {
          const double m = covered[static_cast<size_t>(c)];
          const double share = m > 0.0 ? part(c) / m : 0.0;
          for (int k = 0; k < corners; ++k)
          {
            w[c * corners + k] = share * integrals[static_cast<size_t>(c * corners + k)];
          }
        }
      });
    }
    else if (mp::HasNodalSpace(space, view))
    {
      // The second-order cells' own functions: each one's integral over the
      // covered part, as the pieces measure it (a function spans several
      // simplices, so the surfaces' 90% rule, a per-cell share, is not applied).
      const mp::LargeVector<double>& integrals = op.GetSourceFunctionCovered();
      std::copy(integrals.begin(), integrals.end(), w.begin());
    }
    else if (space == mp::SpaceType::P1)
    {
      // Summed in cell order, in the filter's threads.
      mp::ForCellCornersInOrder(
        view, mpvtk::SMPTaskRunner(), [&](mp::Index c) { return part(c) / corners; },
        [&](mp::Index p, double share) { w[static_cast<size_t>(p)] += share; });
    }
    else
    {
      auto add = [&](vtkIdType begin, vtkIdType end) {
        for (vtkIdType c = begin; c < end; ++c)
        {
          const double m = part(c);
          if (m > 0.0)
          {
            w[static_cast<size_t>(view.ParentOf(c))] += m;
          }
        }
      };
      // One cell per dataset cell: nothing to sum, in the threads; split
      // cells' parts in cell order, in one loop.
      if (!view.Parent || view.OneCellPerParent)
      {
        mpvtk::For(0, view.NumberOfCells, add);
      }
      else
      {
        add(0, view.NumberOfCells);
      }
    }
  }
  return w;
}

const std::vector<double>& SourceWeights::Of(const mp::MortarOperator& op)
{
  const bool known = this->Weights.count(&op) > 0;
  return this->Make(op, this->CoveredTotals(op, !known));
}

void SourceWeights::Weigh(const mp::MortarOperator& op)
{
  this->Make(op, std::vector<double>());
}

namespace
{
/// A Source integral within this fraction of the integral of |u| is zero
/// to round-off (sums of many terms of either sign lose about that much).
constexpr double ZeroIntegralFraction = 1e-10;

/**
 * ConserveSourceIntegral's scale of component k: the projection scaled to
 * the Source's own integral (the facetizations of a curved surface differ
 * in area), when the ratio of the two integrals means something: within
 * [0.5, 2], and the Source's integral above round-off of the integral of
 * |u| (a field of zero mean: the ratio of two round-off sums would scale
 * it by chance). Otherwise unscaled, with one warning per array.
 */
void ScaleToSource(ArrayIntegrals& result, int k, double magnitude, const std::string& name,
  const std::string& role, Messages& messages)
{
  const double ratio = result.Source[k] / result.Target[k];
  const bool zero = std::abs(result.Source[k]) <= ZeroIntegralFraction * magnitude;
  if (!zero && std::isfinite(ratio) && ratio >= 0.5 && ratio <= 2.0)
  {
    result.Factor[k] = ratio;
    result.Target[k] = result.Source[k];
  }
  else if (messages.First("conserve/" + name))
  {
    std::ostringstream text;
    text << "ConserveSourceIntegral: " << name << " (component " << k
         << ") is not scaled: its integral over Source is " << result.Source[k] << " and over "
         << role << " " << result.Target[k];
    if (zero)
    {
      text << " (zero to round-off: the integral of its magnitude is " << magnitude
           << "; nothing to scale).";
    }
    else
    {
      text << " (the ratio must lie within [0.5, 2]).";
    }
    messages.Warn(text.str());
  }
}
} // namespace

ArrayIntegrals Integrate(const ProjectedArray& array, bool conserveSource, const std::string& name,
  const std::string& role, Parts& parts, Messages& messages)
{
  const int nc = array.Components;
  const int width = array.Width;
  const int offset = array.Offset;
  ArrayIntegrals result;
  const std::vector<double>& w = array.Weights;
  const int sourceWidth = array.SourceWidth;
  const int sourceOffset = array.SourceOffset;
  result.Source = mp::SumInBlocks(static_cast<vtkIdType>(w.size()), nc, mpvtk::SMPTaskRunner(),
    [&](vtkIdType j, int k) { return w[j] * array.Source[j * sourceWidth + sourceOffset + k]; });
  const std::vector<char>& valid = *array.System.Valid;
  const std::vector<double>& covered = *array.System.CoveredIntegrals;
  // (An invalid function's value, the fill, may be NaN: left out.)
  result.Target =
    mp::SumInBlocks(array.TargetFunctions, nc, mpvtk::SMPTaskRunner(), [&](vtkIdType f, int k) {
      return valid[f] ? covered[f] * array.Result[f * width + offset + k] : 0.0;
    });
  // The integral of |u| over Source: how large a round-off integral is.
  std::vector<double> magnitude(static_cast<size_t>(nc), 0.0);
  if (conserveSource)
  {
    magnitude = mp::SumInBlocks(
      static_cast<vtkIdType>(w.size()), nc, mpvtk::SMPTaskRunner(), [&](vtkIdType j, int k) {
        return std::abs(w[j] * array.Source[j * sourceWidth + sourceOffset + k]);
      });
  }
  // Totals over the processes (their pieces do not overlap).
  std::vector<double> all(result.Source);
  all.insert(all.end(), result.Target.begin(), result.Target.end());
  all.insert(all.end(), magnitude.begin(), magnitude.end());
  parts.Sum(all.data(), 3 * nc);
  std::copy(all.begin(), all.begin() + nc, result.Source.begin());
  std::copy(all.begin() + nc, all.begin() + 2 * nc, result.Target.begin());
  std::copy(all.begin() + 2 * nc, all.end(), magnitude.begin());
  result.Factor.assign(static_cast<size_t>(nc), 1.0);
  for (int k = 0; k < nc && conserveSource; ++k)
  {
    ScaleToSource(result, k, magnitude[k], name, role, messages);
  }
  return result;
}
} // namespace mpvtk
