// SPDX-License-Identifier: BSD-3-Clause
// The fringe's aggregation (FringeAggregation.h): support integrals, the
// affine extension weights of the ill-posed functions, P^T M P, and the
// products with P and P^T.
#include "Transfer/FringeAggregation.h"

#include "Geometry/CellGeometry.h"
#include "Mesh/CellNeighbors.h"
#include "Mesh/NodalCells.h"
#include "Transfer/CsrBuilder.h"
#include "Transfer/FringeFits.h"
#include "Transfer/FringeFrames.h"
#include "Transfer/FringeRoots.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace mp
{
namespace
{

/// Per point, the cells around it (compressed rows, BuildPointCells').
struct CellsAroundPoints
{
  std::vector<Index> Start;
  std::vector<Index> Cells;

  CellsAroundPoints(const MeshView& mesh, const TaskRunner& runner)
  {
    BuildPointCells(mesh, this->Start, this->Cells, runner);
  }
};

/**
 * How many times its number of terms a fit takes points first: twice, but
 * three times for a quadratic fit of a volume mesh (VolumeFit). Its nearest
 * points, all on one side of i, give weights that carry the free values'
 * errors several times over; half as many more average them out.
 */
size_t FirstPoints(const MeshView& mesh, const StencilFrame& frame, int degree)
{
  return VolumeFit(mesh, frame) && degree == 2 ? 3 : 2;
}

/**
 * The rings a quadratic fit is sought in: FringeVolumeRings on volume
 * meshes (VolumeFit), where one side of a point on an edge or a corner of
 * the target holds the points of a quadratic fit only farther;
 * FringeRings on surfaces and curves.
 */
int QuadraticRings(const MeshView& mesh, const StencilFrame& frame)
{
  return VolumeFit(mesh, frame) ? FringeVolumeRings : FringeRings;
}

/**
 * The fit of `degree` through the nearest points of `points` (sorted by
 * their distance to i on return): the nearest FirstPoints x terms first,
 * then 4 x, then all, until one is stable. Few points keep P^T M P sparse
 * (an aggregated function couples all of its stencil); `points` is cut to
 * the ones used. `rejected`, when given, holds the sorted points of an earlier
 * call that found no fit: a set of nearest points it already tried is not
 * fitted again (the next ring's nearest points are often the same).
 * `ambient` as FitWeights'.
 */
std::vector<double> NearestFit(const MeshView& mesh, const StencilFrame& frame, Index i,
  std::vector<Index>& points, int degree, const FitCoverage* coverage,
  const std::vector<Index>* rejected = nullptr, bool* ambient = nullptr)
{
  const int d = mesh.SpaceDimension;
  const int f = frame.Dimension;
  const int terms = degree == 1 ? f + 1 : (f + 1) * (f + 2) / 2;
  const double* xi = mesh.Point(i);
  std::vector<std::pair<double, Index>> byDistance;
  for (Index k : points)
  {
    double r2 = 0.0;
    for (int a = 0; a < d; ++a)
    {
      r2 += (mesh.Point(k)[a] - xi[a]) * (mesh.Point(k)[a] - xi[a]);
    }
    byDistance.emplace_back(r2, k);
  }
  // Ties (regular meshes have many) broken by the coordinates, not the
  // ids: the stencil must not depend on the numbering.
  std::sort(byDistance.begin(), byDistance.end(),
    [&](const std::pair<double, Index>& a, const std::pair<double, Index>& b) {
      if (a.first != b.first)
      {
        return a.first < b.first;
      }
      const double* p = mesh.Point(a.second);
      const double* q = mesh.Point(b.second);
      return std::lexicographical_compare(p, p + 3, q, q + 3);
    });
  for (size_t r = 0; r < points.size(); ++r)
  {
    points[r] = byDistance[r].second;
  }
  const size_t firstKeep = FirstPoints(mesh, frame, degree) * static_cast<size_t>(terms);
  // (A fit that reproduces the tangent coordinates only, where `ambient`
  // is asked for, is kept while more points are tried for one that
  // reproduces the ambient ones too: at the end of a curved curve the few
  // nearest points, all on one side, amplify too much through the normal
  // offsets, more of them less.)
  std::vector<double> tangent;
  size_t tangentUsed = 0;
  for (const size_t keep : { firstKeep, size_t(4 * terms), points.size() })
  {
    const size_t used = std::min(keep, points.size());
    const bool tried = rejected && used <= rejected->size() &&
      std::min(keep, rejected->size()) == used &&
      std::equal(points.begin(), points.begin() + used, rejected->begin());
    bool reproduces = true;
    std::vector<double> w = tried
      ? std::vector<double>()
      : FitWeights(mesh, frame, i, points, used, degree, &reproduces, coverage);
    if (!w.empty() && (reproduces || !ambient))
    {
      if (ambient)
      {
        *ambient = reproduces;
      }
      points.resize(w.size());
      return w;
    }
    if (!w.empty() && tangent.empty())
    {
      tangent.swap(w);
      tangentUsed = used;
    }
    if (keep >= points.size())
    {
      break;
    }
  }
  if (!tangent.empty())
  {
    *ambient = false;
    points.resize(tangentUsed);
  }
  return tangent;
}

/**
 * One step of the rings around a point: every cell around a point of
 * `ring` not met yet (cellStamp != mark) is stamped and given to
 * `onCell`, and its function points not met yet (stamp != mark; a refined
 * curved simplex's are its parent's nodes, ForEachFunctionPoint) are
 * stamped and listed in `next`, in the order met.
 */
template <typename OnCell>
void GrowRing(const MeshView& mesh, const CellsAroundPoints& around, const std::vector<Index>& ring,
  Index mark, std::vector<Index>& stamp, std::vector<Index>& cellStamp, std::vector<Index>& next,
  OnCell&& onCell)
{
  next.clear();
  for (Index p : ring)
  {
    for (Index q = around.Start[static_cast<size_t>(p)];
         q < around.Start[static_cast<size_t>(p) + 1]; ++q)
    {
      const Index c = around.Cells[static_cast<size_t>(q)];
      if (cellStamp[static_cast<size_t>(c)] == mark)
      {
        continue;
      }
      cellStamp[static_cast<size_t>(c)] = mark;
      onCell(c);
      ForEachFunctionPoint(mesh, c, [&](Index k) {
        if (stamp[static_cast<size_t>(k)] != mark)
        {
          stamp[static_cast<size_t>(k)] = mark;
          next.push_back(k);
        }
      });
    }
  }
}

/**
 * The simplices within FringeRootRings rings of point i (those around it,
 * then those around their corners, ...), in `cells`. The stamps mark with
 * -2 - i (StencilOf's marks are i).
 */
void RootRingCells(const MeshView& mesh, const CellsAroundPoints& around, Index i,
  std::vector<Index>& stamp, std::vector<Index>& cellStamp, std::vector<Index>& cells)
{
  const Index mark = -2 - i;
  std::vector<Index> ring{ i };
  std::vector<Index> next;
  cells.clear();
  stamp[static_cast<size_t>(i)] = mark;
  for (int r = 0; r < FringeRootRings && !ring.empty(); ++r)
  {
    GrowRing(
      mesh, around, ring, mark, stamp, cellStamp, next, [&](Index c) { cells.push_back(c); });
    ring.swap(next);
  }
}

/// Sum |w|.
double Amplification(const std::vector<double>& w)
{
  return std::accumulate(
    w.begin(), w.end(), 0.0, [](double s, double v) { return s + std::abs(v); });
}

/**
 * The affine fit of the `found` points instead of the quadratic `weights`
 * where FringeCellDataAmplification says (`coverage`'s Amplification: cell
 * data): true returned, `points` and `weights` replaced.
 */
bool ShortAffineFit(const MeshView& mesh, const StencilFrame& frame, Index i,
  const std::vector<Index>& found, const FitCoverage* coverage, std::vector<Index>& points,
  std::vector<double>& weights)
{
  if (!coverage || !(coverage->Amplification > 0.0) ||
    !(coverage->Fraction[i] < FringeCellDataAffineFraction) ||
    Amplification(weights) <= coverage->Amplification)
  {
    return false;
  }
  std::vector<Index> candidates = found;
  bool ambient = true;
  std::vector<double> affine =
    NearestFit(mesh, frame, i, candidates, 1, coverage, nullptr, &ambient);
  if (affine.empty() || !ambient || Amplification(affine) > FringeCellDataAffineAmplification)
  {
    return false;
  }
  points.swap(candidates);
  weights.swap(affine);
  return true;
}

/**
 * The ill-posed function i's fit: free points ring by ring, a quadratic fit
 * within QuadraticRings rings (true returned), else the affine fit of the
 * first ring that allows one, up to FringeSearchRings; none when no ring
 * allows one.
 */
bool FitStencil(const MeshView& mesh, const CellsAroundPoints& around, Index i,
  const std::vector<char>& usable, const FitCoverage* coverage, std::vector<Index>& stamp,
  std::vector<Index>& cellStamp, std::vector<Index>& points, std::vector<double>& weights)
{
  const Index first = around.Start[static_cast<size_t>(i)];
  const StencilFrame frame = StencilFrameOf(
    mesh, i, around.Cells.data() + first, around.Start[static_cast<size_t>(i) + 1] - first);
  const int quadraticRings = QuadraticRings(mesh, frame);
  std::vector<Index> ring{ i };
  std::vector<Index> next;
  std::vector<Index> affinePoints;
  std::vector<double> affine;
  bool affineAmbient = false; // affine reproduces the ambient affine functions
  std::vector<Index> found;
  std::vector<Index> rejected;      // the last ring's points, sorted: no quadratic fit
  std::vector<Index> tangentPoints; // the first quadratic fit of the tangent coordinates only
  std::vector<double> tangentWeights;
  points.clear();
  weights.clear();
  stamp[static_cast<size_t>(i)] = i;
  for (int r = 0; r < FringeSearchRings && !ring.empty(); ++r)
  {
    GrowRing(mesh, around, ring, i, stamp, cellStamp, next, [](Index) {});
    for (Index k : next)
    {
      if (usable[static_cast<size_t>(k)])
      {
        found.push_back(k);
      }
    }
    // A quadratic fit where the rings so far allow one (its extrapolation
    // error is of third order), else an affine one from the first ring
    // that allows it. Beyond QuadraticRings only the affine fit is sought.
    const bool inner = r < quadraticRings;
    if (inner)
    {
      points = found;
      bool ambient = true;
      weights = NearestFit(mesh, frame, i, points, 2, coverage, &rejected, &ambient);
      if (!weights.empty() && ambient)
      {
        return !ShortAffineFit(mesh, frame, i, found, coverage, points, weights);
      }
      if (weights.empty())
      {
        rejected = points;
      }
      else if (tangentWeights.empty())
      {
        tangentPoints.swap(points);
        tangentWeights.swap(weights);
      }
    }
    // (On a curved surface or curve a fit that reproduces the tangent
    // coordinates only, through too few points for their normal ones too,
    // gives way to one from a later ring that does: a quadratic one within
    // QuadraticRings, an affine one up to FringeSearchRings. At the end of
    // a curved curve the nearest points lie on one side only, and a linear
    // field stays exact only through the normal offsets of more of them.)
    if (affine.empty() || !affineAmbient)
    {
      std::vector<Index> candidates = found;
      bool ambient = true;
      std::vector<double> fit =
        NearestFit(mesh, frame, i, candidates, 1, coverage, nullptr, &ambient);
      if (!fit.empty() && (affine.empty() || ambient))
      {
        affinePoints.swap(candidates);
        affine.swap(fit);
        affineAmbient = ambient;
      }
    }
    if (!affine.empty() && affineAmbient && !(inner && r + 1 < quadraticRings))
    {
      break;
    }
    ring.swap(next);
  }
  // (A quadratic fit of the tangent coordinates before an affine one of
  // them: the first found, as where no fit reproduces the ambient ones.)
  const bool tangentQuadratic = !tangentWeights.empty() && !affineAmbient;
  points.swap(tangentQuadratic ? tangentPoints : affinePoints);
  weights.swap(tangentQuadratic ? tangentWeights : affine);
  if (weights.empty())
  {
    points.clear(); // no stable fit: ExtendFringe frees or drops the function
  }
  return tangentQuadratic;
}

/**
 * The ill-posed function i's stencil and weights: its fit (FitStencil); on
 * a second-order target (`roots` not empty) where that fit is affine or
 * none, a root cell's own function instead when one is within
 * FringeRootAmplification (FringeRoots.h).
 */
void StencilOf(const MeshView& mesh, const CellsAroundPoints& around, Index i,
  const std::vector<char>& usable, const FitCoverage* coverage, const std::vector<char>& roots,
  std::vector<Index>& stamp, std::vector<Index>& cellStamp, std::vector<Index>& points,
  std::vector<double>& weights)
{
  if (FitStencil(mesh, around, i, usable, coverage, stamp, cellStamp, points, weights) ||
    roots.empty())
  {
    return;
  }
  std::vector<Index> cells;
  std::vector<Index> rootPoints;
  std::vector<double> rootWeights;
  RootRingCells(mesh, around, i, stamp, cellStamp, cells);
  if (RootExtension(mesh, i, cells, roots, usable, rootPoints, rootWeights))
  {
    points.swap(rootPoints);
    weights.swap(rootWeights);
  }
}

/// Appends row `x` of M times P to `row` (pairs of column and value, unsorted).
void AddRowTimesP(const CsrMatrix& mass, Index x, double scale, const FringeExtension& ext,
  std::vector<std::pair<Column, double>>& row)
{
  for (Index p = mass.RowStart[x]; p < mass.RowStart[x + 1]; ++p)
  {
    const Column b = mass.ColumnIndex[p];
    const double v = scale * mass.Values[p];
    if (!ext.Aggregated[static_cast<size_t>(b)])
    {
      row.emplace_back(b, v);
      continue;
    }
    for (Index q = ext.P.RowStart[b]; q < ext.P.RowStart[b + 1]; ++q)
    {
      row.emplace_back(ext.P.ColumnIndex[q], v * ext.P.Values[q]);
    }
  }
}

/// P^T's rows: per free function, the aggregated functions whose stencils hold it, with their weights.
struct Referrers
{
  std::vector<Index> Start;
  std::vector<std::pair<Index, double>> Rows;

  Referrers(const FringeExtension& ext, Index n)
  {
    GroupInRows(
      n,
      [&](auto put) {
        for (Index a = 0; a < n; ++a)
        {
          for (Index q = ext.Aggregated[a] ? ext.P.RowStart[a] : 0;
               ext.Aggregated[a] && q < ext.P.RowStart[a + 1]; ++q)
          {
            put(ext.P.ColumnIndex[q], std::pair<Index, double>(a, ext.P.Values[q]));
          }
        }
      },
      this->Start, this->Rows);
  }
};

/// Row j of P^T M P (its columns ascending) when it differs from M's, summed in `sum`.
void ChangedRow(const CsrMatrix& mass, const FringeExtension& ext, const Referrers& refs, Index j,
  RowAccumulator& sum, RowList& terms, RowList& out)
{
  if (ext.Aggregated[static_cast<size_t>(j)])
  {
    out.emplace_back(static_cast<Column>(j), 1.0); // decoupled: its value comes from P
    return;
  }
  // Row j of P^T M P = (M P)_j + sum over the rows a aggregated onto j of w_aj (M P)_a.
  terms.clear();
  AddRowTimesP(mass, j, 1.0, ext, terms);
  for (Index r = refs.Start[j]; r < refs.Start[j + 1]; ++r)
  {
    AddRowTimesP(mass, refs.Rows[static_cast<size_t>(r)].first,
      refs.Rows[static_cast<size_t>(r)].second, ext, terms);
  }
  for (const auto& term : terms)
  {
    sum.Add(term.first, term.second);
  }
  sum.TakeInto(true, out);
}

/**
 * Per row of M, its place among the rows of P^T M P that differ from M's
 * (the aggregated ones, those referred to, those with an aggregated
 * column), or -1; `changed` lists them.
 */
std::vector<Index> ChangedRows(const CsrMatrix& mass, const FringeExtension& ext,
  const Referrers& refs, const TaskRunner& runner, std::vector<Index>& changed)
{
  const Index n = mass.Rows;
  std::vector<Index> slot(static_cast<size_t>(n), -1);
  runner.ForRanges(n, [&](Index begin, Index end) {
    for (Index j = begin; j < end; ++j)
    {
      bool changes = ext.Aggregated[j] || refs.Start[j + 1] > refs.Start[j];
      for (Index p = mass.RowStart[j]; p < mass.RowStart[j + 1] && !changes; ++p)
      {
        changes = ext.Aggregated[mass.ColumnIndex[p]] != 0;
      }
      slot[static_cast<size_t>(j)] = changes ? 0 : -1;
    }
    return 0;
  });
  changed.clear();
  for (Index j = 0; j < n; ++j)
  {
    if (slot[static_cast<size_t>(j)] >= 0)
    {
      slot[static_cast<size_t>(j)] = static_cast<Index>(changed.size());
      changed.push_back(j);
    }
  }
  return slot;
}

/**
 * The ill-posed functions' stencils and weights (StencilOf), each on its
 * own (a task marks the points it has met in its own array): the tasks'
 * ranges of ill-posed functions give the same stencils as one loop.
 */
void Stencils(const MeshView& mesh, const std::vector<Index>& ill, const std::vector<char>& usable,
  const FitCoverage* coverage, const TaskRunner& runner, std::vector<std::vector<Index>>& stencils,
  std::vector<std::vector<double>>& weights)
{
  const CellsAroundPoints around(mesh, runner);
  const Index n = static_cast<Index>(usable.size());
  // Per parent of a second-order target: whether it can be a root (FringeRoots.h).
  std::vector<char> roots;
  if (mesh.Nodal)
  {
    roots.resize(static_cast<size_t>(mesh.Parents()));
    for (Index p = 0; p < mesh.Parents(); ++p)
    {
      roots[static_cast<size_t>(p)] = IsAffineRoot(mesh, p);
    }
  }
  stencils.assign(ill.size(), {});
  weights.assign(ill.size(), {});
  runner.ForRanges(
    static_cast<Index>(ill.size()),
    [&](Index begin, Index end) {
      std::vector<Index> stamp(static_cast<size_t>(n), -1);
      std::vector<Index> cellStamp(static_cast<size_t>(mesh.NumberOfCells), -1);
      for (Index a = begin; a < end; ++a)
      {
        StencilOf(mesh, around, ill[static_cast<size_t>(a)], usable, coverage, roots, stamp,
          cellStamp, stencils[static_cast<size_t>(a)], weights[static_cast<size_t>(a)]);
      }
      return 0;
    },
    256);
}

/**
 * P over `n` functions: identity rows, the rows of ill[a] with a stencil
 * its weights (columns ascending, or in the stencil's order).
 */
CsrMatrix ExtensionMatrix(Index n, const std::vector<Index>& ill,
  const std::vector<std::vector<Index>>& stencils, const std::vector<std::vector<double>>& weights,
  bool stencilOrder)
{
  std::vector<Index> of(static_cast<size_t>(n), -1); // per function: its a, when aggregated
  for (size_t a = 0; a < ill.size(); ++a)
  {
    of[static_cast<size_t>(ill[a])] = stencils[a].empty() ? -1 : static_cast<Index>(a);
  }
  RowList row;
  return BuildCsr(
    n, n,
    [&](Index i) {
      const Index a = of[static_cast<size_t>(i)];
      return a < 0 ? Index(1) : static_cast<Index>(stencils[static_cast<size_t>(a)].size());
    },
    [&](Index i, Column* column, double* value) {
      const Index a = of[static_cast<size_t>(i)];
      if (a < 0)
      {
        *column = static_cast<Column>(i);
        *value = 1.0;
        return;
      }
      row.clear();
      for (size_t k = 0; k < stencils[static_cast<size_t>(a)].size(); ++k)
      {
        row.emplace_back(static_cast<Column>(stencils[static_cast<size_t>(a)][k]),
          weights[static_cast<size_t>(a)][k]);
      }
      if (!stencilOrder)
      {
        std::sort(row.begin(), row.end());
      }
      for (const auto& entry : row)
      {
        *column++ = entry.first;
        *value++ = entry.second;
      }
    });
}
} // namespace

LargeVector<double> SupportIntegrals(const MeshView& mesh)
{
  LargeVector<double> support(static_cast<size_t>(mesh.NumberOfPoints), 0.0);
  const int corners = mesh.CornersPerCell();
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const CellCorners cell = mesh.Cell(c);
    const double measure = SimplexMeasure(mesh, c);
    for (int k = 0; k < corners; ++k)
    {
      support[static_cast<size_t>(cell[k])] += measure / corners; // int of a hat over a simplex
    }
  }
  return support;
}

FringeExtension ExtendFringe(const MeshView& mesh, const std::vector<char>& valid,
  const std::vector<double>& fraction, double threshold, double drop, const TaskRunner& runner,
  bool stencilOrder, double coveragePower, double quadraticAmplification)
{
  FringeExtension ext;
  const Index n = static_cast<Index>(valid.size());
  ext.Aggregated.assign(static_cast<size_t>(n), 0);
  ext.Dropped.assign(static_cast<size_t>(n), 0);
  std::vector<char> usable(static_cast<size_t>(n), 0);
  std::vector<Index> ill;
  for (Index i = 0; i < n; ++i)
  {
    const bool wellCovered = fraction[i] >= threshold;
    usable[i] = valid[i] && wellCovered;
    if (valid[i] && !wellCovered)
    {
      ill.push_back(i);
    }
  }
  if (ill.empty())
  {
    return ext;
  }
  std::vector<std::vector<Index>> stencils;
  std::vector<std::vector<double>> weights;
  const FitCoverage coverage{ fraction.data(), coveragePower, quadraticAmplification };
  const bool weighed = coveragePower > 0.0 || quadraticAmplification > 0.0;
  Stencils(mesh, ill, usable, weighed ? &coverage : nullptr, runner, stencils, weights);
  for (size_t a = 0; a < ill.size(); ++a)
  {
    const bool extended = !stencils[a].empty();
    // (Stranded: no stable stencil, and too little covered to keep its own fit.)
    const bool stranded = !extended && fraction[ill[a]] < FringeStrandedDropFraction;
    ext.Aggregated[static_cast<size_t>(ill[a])] = extended;
    ext.Dropped[static_cast<size_t>(ill[a])] = (extended && fraction[ill[a]] < drop) || stranded;
    ext.Count += extended;
    ext.Stranded += stranded;
  }
  ext.P = ExtensionMatrix(n, ill, stencils, weights, stencilOrder);
  return ext;
}

CsrMatrix AggregatedMass(
  const CsrMatrix& mass, const FringeExtension& ext, const TaskRunner& runner)
{
  const Index n = mass.Rows;
  const Referrers refs(ext, n);
  std::vector<Index> changed;
  const std::vector<Index> slot = ChangedRows(mass, ext, refs, runner, changed);
  // The changed rows, each on its own (the same terms in the same order
  // whatever the tasks); the others are M's.
  std::vector<RowList> rows(changed.size());
  runner.ForRanges(
    static_cast<Index>(changed.size()),
    [&](Index begin, Index end) {
      RowAccumulator sum(n);
      RowList terms;
      for (Index r = begin; r < end; ++r)
      {
        ChangedRow(mass, ext, refs, changed[static_cast<size_t>(r)], sum, terms,
          rows[static_cast<size_t>(r)]);
      }
      return 0;
    },
    256);
  CsrMatrix out = BuildCsr(
    n, mass.Columns,
    [&](Index j) {
      const Index r = slot[static_cast<size_t>(j)];
      return r < 0 ? mass.RowStart[j + 1] - mass.RowStart[j]
                   : static_cast<Index>(rows[static_cast<size_t>(r)].size());
    },
    [&](Index j, Column* column, double* value) {
      const Index r = slot[static_cast<size_t>(j)];
      if (r < 0)
      {
        std::copy(mass.ColumnIndex.data() + mass.RowStart[j],
          mass.ColumnIndex.data() + mass.RowStart[j + 1], column);
        std::copy(
          mass.Values.data() + mass.RowStart[j], mass.Values.data() + mass.RowStart[j + 1], value);
        return;
      }
      for (const auto& entry : rows[static_cast<size_t>(r)])
      {
        *column++ = entry.first;
        *value++ = entry.second;
      }
    },
    &runner);
  return out;
}

void RestrictToFree(const FringeExtension& ext, const double* x, double* y, int c)
{
  const Index n = ext.P.Rows;
  std::copy(x, x + n * c, y);
  for (Index a = 0; a < n; ++a)
  {
    if (!ext.Aggregated[static_cast<size_t>(a)])
    {
      continue;
    }
    for (Index q = ext.P.RowStart[a]; q < ext.P.RowStart[a + 1]; ++q)
    {
      const Index k = ext.P.ColumnIndex[q];
      for (int m = 0; m < c; ++m)
      {
        y[k * c + m] += ext.P.Values[q] * x[a * c + m];
      }
    }
    std::fill(y + a * c, y + (a + 1) * c, 0.0);
  }
}

void ExtendFromFree(const FringeExtension& ext, double* x, int c)
{
  const Index n = ext.P.Rows;
  for (Index a = 0; a < n; ++a)
  {
    if (!ext.Aggregated[static_cast<size_t>(a)])
    {
      continue;
    }
    std::fill(x + a * c, x + (a + 1) * c, 0.0);
    for (Index q = ext.P.RowStart[a]; q < ext.P.RowStart[a + 1]; ++q)
    {
      const Index k = ext.P.ColumnIndex[q];
      for (int m = 0; m < c; ++m)
      {
        x[a * c + m] += ext.P.Values[q] * x[k * c + m];
      }
    }
  }
}
} // namespace mp
