// SPDX-License-Identifier: BSD-3-Clause
// The fringe's aggregation (FringeAggregation.h): support integrals, the
// affine extension weights of the ill-posed functions, P^T M P, and the
// products with P and P^T.
#include "Transfer/FringeAggregation.h"

#include "Geometry/CellGeometry.h"
#include "Mesh/CellNeighbors.h"
#include "Transfer/CsrBuilder.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
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

/// The monomials of degree <= `degree` (1 or 2) at y (d coordinates): 1, y_a, y_a y_b.
int Monomials(const double* y, int d, int degree, double* into)
{
  int m = 0;
  into[m++] = 1.0;
  for (int a = 0; a < d; ++a)
  {
    into[m++] = y[a];
  }
  for (int a = 0; degree > 1 && a < d; ++a)
  {
    for (int b = a; b < d; ++b)
    {
      into[m++] = y[a] * y[b];
    }
  }
  return m;
}

/**
 * The largest sum of |w_ik| a quadratic extension may have in 2D: the
 * factor by which it can amplify an oscillation of the free values.
 * One-sided quadratic extrapolations reach a dozen and more (three points
 * on a line: 3, -3, 1 already 7); such weights couple the stencil's
 * functions with alternating signs in P^T M P and widen its spectrum (the
 * conjugate gradients then need up to three times the iterations). The
 * affine fit, taken beyond this, is of second order only: at a curved
 * boundary it leaves the fringe's error several times the interior's, so
 * the bound keeps what quadratic fits it can.
 */
constexpr double QuadraticAmplification = 8.0;

/**
 * The same bound in 3D. A corner of a volume target reaching out of the
 * source is extrapolated along up to three directions at once: the affine
 * fit's error there (its weights times the squared distances, a cell and
 * two away) is many times the interior's, while the free values a
 * quadratic fit amplifies are smooth along the fringe (they are errors of
 * the same projection, of second order). A quadratic fit through the
 * 15 and more points of one side of i is accepted up to this amplification.
 */
constexpr double VolumeQuadraticAmplification = 12.0;

/// The amplification a quadratic fit in `d` dimensions may have.
double AmplificationBound(int d)
{
  return d == 3 ? VolumeQuadraticAmplification : QuadraticAmplification;
}

/**
 * The weights of `points` that give, at point i, the value of the
 * least-squares polynomial fit of degree `degree` through them (the
 * minimum-norm weights reproducing those polynomials at i), or empty when
 * the points do not allow a stable fit: when they do not spread well
 * (nearly on a line, a plane or a conic), or, quadratic, when the weights
 * amplify more than AmplificationBound. Degree 1 or 2: either
 * reproduces affine functions and sums to 1.
 */
std::vector<double> FitWeights(
  const MeshView& mesh, Index i, const std::vector<Index>& points, size_t keep, int degree)
{
  const int d = mesh.SpaceDimension;
  const int terms = degree == 1 ? d + 1 : (d + 1) * (d + 2) / 2;
  const double* xi = mesh.Point(i);
  const Index m = static_cast<Index>(keep);
  if (m < (degree == 1 ? terms : 3 * terms / 2))
  {
    return {};
  }
  double h = 0.0;
  for (size_t r = 0; r < keep; ++r)
  {
    const Index k = points[r];
    for (int a = 0; a < d; ++a)
    {
      h = std::max(h, std::abs(mesh.Point(k)[a] - xi[a]));
    }
  }
  if (!(h > 0.0))
  {
    return {};
  }
  // Monomials of (x_k - x_i) / h: coordinates of order 1 about i; each
  // point weighed by omega_k, larger near i (the fit is evaluated at i:
  // near points tell most about it). The normal matrix G = sum_k omega_k
  // v_k v_k^T (v_k the monomials at k) summed row by row, at most 10 x 10
  // on the stack; the monomials made again for the weights rather than
  // kept (no matrix of points x terms to allocate per fit).
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 10, 10>;
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 10, 1>;
  auto monomialsAt = [&](Index r, double& omega, SmallVector& v) {
    double y[3];
    double distance2 = 0.0;
    for (int a = 0; a < d; ++a)
    {
      y[a] = (mesh.Point(points[static_cast<size_t>(r)])[a] - xi[a]) / h;
      distance2 += y[a] * y[a];
    }
    omega = 1.0 / ((distance2 + 0.25) * (distance2 + 0.25));
    Monomials(y, d, degree, v.data());
  };
  Small G = Small::Zero(terms, terms);
  SmallVector v(terms);
  double omegaSum = 0.0;
  for (Index r = 0; r < m; ++r)
  {
    double omega;
    monomialsAt(r, omega, v);
    G.selfadjointView<Eigen::Lower>().rankUpdate(v, omega);
    omegaSum += omega;
  }
  G = G.selfadjointView<Eigen::Lower>();
  G /= omegaSum;
  SmallVector e = SmallVector::Zero(terms);
  e(0) = 1.0; // the fit's value at i (the origin of the coordinates)
  // The weighted fit's value at i: w_k = omega_k v_k . G^-1 e / sum omega.
  const SmallVector c = G.ldlt().solve(e);
  std::vector<double> w(static_cast<size_t>(m));
  double amplification = 0.0;
  for (Index r = 0; r < m; ++r)
  {
    double omega;
    monomialsAt(r, omega, v);
    w[static_cast<size_t>(r)] = omega * v.dot(c) / omegaSum;
    amplification += std::abs(w[static_cast<size_t>(r)]);
  }
  // (Not "> bound": a singular G gives NaN weights, rejected too.) Most
  // one-sided quadratic fits stop here, before the spectrum's cost.
  if (degree == 2 && !(amplification <= AmplificationBound(d)))
  {
    return {};
  }
  // Points nearly on a line or a plane (or a conic) do not determine the
  // fit, whatever its weights (on a Gmsh wedge pair, quadratic fits
  // accepted on their amplification alone gave 17 times the interior's
  // error).
  if (Eigen::SelfAdjointEigenSolver<Small>(G, Eigen::EigenvaluesOnly).eigenvalues().minCoeff() <
    (degree == 1 ? 1e-2 : 1e-4))
  {
    return {};
  }
  return w;
}

/**
 * How many times its number of terms a fit takes points first: twice, but
 * three times for a quadratic fit in 3D. Its 20 nearest points, all on one
 * side of i, give weights that carry the free values' errors several times
 * over; half as many more average them out.
 */
size_t FirstPoints(int d, int degree)
{
  return d == 3 && degree == 2 ? 3 : 2;
}

/**
 * The fit of `degree` through the nearest points of `points` (sorted by
 * their distance to i on return): the nearest FirstPoints x terms first,
 * then 4 x, then all, until one is stable. Few points keep P^T M P sparse
 * (an aggregated function couples all of its stencil); `points` is cut to
 * the ones used. `rejected`, when given, holds the sorted points of an earlier
 * call that found no fit: a set of nearest points it already tried is not
 * fitted again (the next ring's nearest points are often the same).
 */
std::vector<double> NearestFit(const MeshView& mesh, Index i, std::vector<Index>& points,
  int degree, const std::vector<Index>* rejected = nullptr)
{
  const int d = mesh.SpaceDimension;
  const int terms = degree == 1 ? d + 1 : (d + 1) * (d + 2) / 2;
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
  const size_t first = FirstPoints(d, degree) * static_cast<size_t>(terms);
  for (const size_t keep : { first, size_t(4 * terms), points.size() })
  {
    const size_t used = std::min(keep, points.size());
    const bool tried = rejected && used <= rejected->size() &&
      std::min(keep, rejected->size()) == used &&
      std::equal(points.begin(), points.begin() + used, rejected->begin());
    std::vector<double> w =
      tried ? std::vector<double>() : FitWeights(mesh, i, points, used, degree);
    if (!w.empty())
    {
      points.resize(w.size());
      return w;
    }
    if (keep >= points.size())
    {
      break;
    }
  }
  return {};
}

/**
 * The rings a quadratic fit is sought in: FringeRings in 2D;
 * FringeVolumeRings in 3D, where one side of a point on an edge or a corner
 * of the target holds the 15 points of a quadratic fit only farther.
 */
int QuadraticRings(int d)
{
  return d == 3 ? FringeVolumeRings : FringeRings;
}

/**
 * The ill-posed function i's stencil and weights: free points ring by ring,
 * a quadratic fit within QuadraticRings rings, else the affine fit of the
 * first ring that allows one, up to FringeSearchRings; none when no ring
 * allows one.
 */
void StencilOf(const MeshView& mesh, const CellsAroundPoints& around, Index i,
  const std::vector<char>& usable, std::vector<Index>& stamp, std::vector<Index>& cellStamp,
  std::vector<Index>& points, std::vector<double>& weights)
{
  const int corners = mesh.CornersPerCell();
  const int quadraticRings = QuadraticRings(mesh.SpaceDimension);
  std::vector<Index> ring{ i };
  std::vector<Index> next;
  std::vector<Index> affinePoints;
  std::vector<double> affine;
  std::vector<Index> found;
  std::vector<Index> rejected; // the last ring's points, sorted: no quadratic fit
  points.clear();
  weights.clear();
  stamp[static_cast<size_t>(i)] = i;
  for (int r = 0; r < FringeSearchRings && !ring.empty(); ++r)
  {
    next.clear();
    for (Index p : ring)
    {
      for (Index q = around.Start[static_cast<size_t>(p)];
           q < around.Start[static_cast<size_t>(p) + 1]; ++q)
      {
        // (A cell met from an earlier point of the rings has its corners stamped.)
        const Index c = around.Cells[static_cast<size_t>(q)];
        if (cellStamp[static_cast<size_t>(c)] == i)
        {
          continue;
        }
        cellStamp[static_cast<size_t>(c)] = i;
        const CellCorners cell = mesh.Cell(c);
        for (int a = 0; a < corners; ++a)
        {
          const Index k = cell[a];
          if (stamp[static_cast<size_t>(k)] != i)
          {
            stamp[static_cast<size_t>(k)] = i;
            next.push_back(k);
            if (usable[static_cast<size_t>(k)])
            {
              found.push_back(k);
            }
          }
        }
      }
    }
    // A quadratic fit where the rings so far allow one (its extrapolation
    // error is of third order), else an affine one from the first ring
    // that allows it. Beyond QuadraticRings only the affine fit is sought.
    const bool inner = r < quadraticRings;
    if (inner)
    {
      points = found;
      weights = NearestFit(mesh, i, points, 2, &rejected);
      if (!weights.empty())
      {
        return;
      }
      rejected = points;
    }
    if (affine.empty())
    {
      affinePoints = found;
      affine = NearestFit(mesh, i, affinePoints, 1);
    }
    if (!affine.empty() && !(inner && r + 1 < quadraticRings))
    {
      break;
    }
    ring.swap(next);
  }
  points.swap(affinePoints);
  weights.swap(affine);
  if (weights.empty())
  {
    points.clear(); // no stable fit: ExtendFringe frees or drops the function
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
  const TaskRunner& runner, std::vector<std::vector<Index>>& stencils,
  std::vector<std::vector<double>>& weights)
{
  const CellsAroundPoints around(mesh, runner);
  const Index n = static_cast<Index>(usable.size());
  stencils.assign(ill.size(), {});
  weights.assign(ill.size(), {});
  runner.ForRanges(
    static_cast<Index>(ill.size()),
    [&](Index begin, Index end) {
      std::vector<Index> stamp(static_cast<size_t>(n), -1);
      std::vector<Index> cellStamp(static_cast<size_t>(mesh.NumberOfCells), -1);
      for (Index a = begin; a < end; ++a)
      {
        StencilOf(mesh, around, ill[static_cast<size_t>(a)], usable, stamp, cellStamp,
          stencils[static_cast<size_t>(a)], weights[static_cast<size_t>(a)]);
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
  bool stencilOrder)
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
  Stencils(mesh, ill, usable, runner, stencils, weights);
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
