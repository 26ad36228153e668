// SPDX-License-Identifier: BSD-3-Clause
#include "MortarProjector.h"

#include "CellNeighbors.h"
#include "LargeArray.h"
#include "PairSearch.h"
#include "TetrahedronIntersector.h"
#include "TriangleIntersector.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <chrono>
#include <cmath>

namespace mp
{
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, Index>;
using Triplet = Eigen::Triplet<double, Index>;
using Column = std::int32_t;

struct MortarProjector::Internals
{
  /// M_tt over the covered part, in CSR with the target mesh's point graph
  /// as pattern; rows of invalid points hold a 1 on the diagonal.
  LargeVector<Index> RowStart;
  /// Column indices in 32 bits (Build() refuses meshes with 2^31 points or
  /// more): the solve streams them once per iteration.
  LargeVector<Column> Columns;
  LargeVector<double> Values;
  SparseMatrix Mts;                ///< target x source points, when kept
  LargeVector<double> Rhs;         ///< M_ts u_s for the fields given to Build
  int Components = 0;
  mutable std::unique_ptr<Eigen::SimplicialLDLT<SparseMatrix>> Direct; ///< fallback only

  /// Concurrent tasks for the solve (ProjectionOptions::Tasks, RunTasks).
  int Tasks = 1;
  int MaxIterations = 500; ///< ProjectionOptions::MaxIterations
  std::function<void(int, const std::function<void(int)>&)> RunTasks;

  Index Size() const { return static_cast<Index>(this->RowStart.size()) - 1; }

  /**
   * Runs body(begin, end) over [0, n) split into this->Tasks ranges, at
   * once when a runner is set, and returns the sum of what the calls return,
   * added in range order (the same result for the same number of tasks).
   */
  template <class Body>
  auto ForRanges(Index n, const Body& body) const -> decltype(body(Index(0), Index(0)))
  {
    using Sum = decltype(body(Index(0), Index(0)));
    const int tasks = this->RunTasks ? static_cast<int>(std::max<Index>(1,
                                         std::min<Index>(this->Tasks, n / 4096)))
                                     : 1;
    if (tasks == 1)
    {
      return body(Index(0), n);
    }
    std::vector<Sum> partial(static_cast<size_t>(tasks));
    this->RunTasks(tasks, [&](int k) { partial[k] = body(n * k / tasks, n * (k + 1) / tasks); });
    Sum sum = partial[0];
    for (int k = 1; k < tasks; ++k)
    {
      sum += partial[k];
    }
    return sum;
  }
  /// Per right-hand side sums, added component-wise (for ForRanges).
  struct Sums
  {
    std::vector<double> Values;
    Sums() = default;
    explicit Sums(size_t n)
      : Values(n, 0.0)
    {
    }
    Sums& operator+=(const Sums& o)
    {
      for (size_t k = 0; k < this->Values.size(); ++k)
      {
        this->Values[k] += o.Values[k];
      }
      return *this;
    }
  };

  /**
   * Y = M_tt X on rows [begin, end) for `c` vectors stored side by side
   * (row i holds entries i*c .. i*c + c-1): the matrix is read once for all.
   */
  template <int FixedC>
  void Multiply(const double* X, double* Y, int dynamicC, Index begin, Index end) const
  {
    const int c = FixedC > 0 ? FixedC : dynamicC;
    for (Index i = begin; i < end; ++i)
    {
      double* y = Y + i * c;
      std::fill(y, y + c, 0.0);
      for (Index p = this->RowStart[i]; p < this->RowStart[i + 1]; ++p)
      {
        const double v = this->Values[p];
        const double* x = X + static_cast<Index>(this->Columns[p]) * c;
        for (int k = 0; k < c; ++k)
        {
          y[k] += v * x[k];
        }
      }
    }
  }

  /**
   * Preconditioned conjugate gradients (Jacobi) for M_tt X = B, `c`
   * right-hand sides stored side by side and iterated in lockstep (each with
   * its own step lengths; one that has converged stops changing), so that
   * every iteration reads the matrix once for all of them. Started from the
   * lumped-mass solution x_i = b_i / sum_k (M_tt)_ik, already second-order
   * accurate for smooth fields (fewer iterations). Row ranges run as
   * concurrent tasks. converged[k] tells whether the residual of column k
   * fell below `tolerance` times its |b|.
   */
  void ConjugateGradients(const double* B, double* X, int c, double tolerance, int maxIterations,
    std::vector<char>& converged) const
  {
    // Compile-time widths for the usual few fields (scalars, vectors).
    switch (c)
    {
      case 1:
        return this->ConjugateGradients<1>(B, X, c, tolerance, maxIterations, converged);
      case 2:
        return this->ConjugateGradients<2>(B, X, c, tolerance, maxIterations, converged);
      case 3:
        return this->ConjugateGradients<3>(B, X, c, tolerance, maxIterations, converged);
      case 4:
        return this->ConjugateGradients<4>(B, X, c, tolerance, maxIterations, converged);
      default:
        return this->ConjugateGradients<0>(B, X, c, tolerance, maxIterations, converged);
    }
  }
  template <int FixedC>
  void ConjugateGradients(const double* B, double* X, int dynamicC, double tolerance,
    int maxIterations, std::vector<char>& converged) const
  {
    const int c = FixedC > 0 ? FixedC : dynamicC;
    const Index n = this->Size();
    const size_t size = static_cast<size_t>(n) * c;
    LargeVector<double> r(size);
    LargeVector<double> z(size);
    LargeVector<double> p(size);
    LargeVector<double> q(size);
    LargeVector<double> inverseDiagonal(static_cast<size_t>(n));
    converged.assign(static_cast<size_t>(c), 0);
    const Sums bb = this->ForRanges(n, [&](Index begin, Index end) {
      Sums sum(c);
      for (Index i = begin; i < end; ++i)
      {
        double rowSum = 0.0;
        for (Index k = this->RowStart[i]; k < this->RowStart[i + 1]; ++k)
        {
          rowSum += this->Values[k];
        }
        inverseDiagonal[i] = 1.0 / this->Values[this->Find(i, i)];
        for (int k = 0; k < c; ++k)
        {
          const double b = B[i * c + k];
          X[i * c + k] = rowSum > 0.0 ? b / rowSum : 0.0;
          sum.Values[k] += b * b;
        }
      }
      return sum;
    });
    std::vector<double> goal(static_cast<size_t>(c));
    for (int k = 0; k < c; ++k)
    {
      goal[k] = tolerance * tolerance * bb.Values[k];
    }
    this->ForRanges(n, [&](Index begin, Index end) {
      this->Multiply<FixedC>(X, q.data(), c, begin, end);
      return 0.0;
    });
    // Residuals, and the first direction; per column |r|^2 and r.z.
    Sums sums = this->ForRanges(n, [&](Index begin, Index end) {
      Sums part(2 * c);
      for (Index i = begin; i < end; ++i)
      {
        for (int k = 0; k < c; ++k)
        {
          const Index e = i * c + k;
          r[e] = B[e] - q[e];
          z[e] = inverseDiagonal[i] * r[e];
          p[e] = z[e];
          part.Values[k] += r[e] * r[e];
          part.Values[c + k] += r[e] * z[e];
        }
      }
      return part;
    });
    std::vector<double> rz(static_cast<size_t>(c));
    std::vector<double> alpha(static_cast<size_t>(c));
    std::vector<double> beta(static_cast<size_t>(c));
    int open = 0;
    for (int k = 0; k < c; ++k)
    {
      // A zero field is converged at its start (the lumped solution is 0).
      converged[k] = bb.Values[k] == 0.0 || sums.Values[k] <= goal[k];
      open += !converged[k];
      rz[k] = sums.Values[c + k];
    }
    for (int iteration = 0; iteration < maxIterations && open > 0; ++iteration)
    {
      const Sums pq = this->ForRanges(n, [&](Index begin, Index end) {
        this->Multiply<FixedC>(p.data(), q.data(), c, begin, end);
        Sums part(c);
        for (Index i = begin; i < end; ++i)
        {
          for (int k = 0; k < c; ++k)
          {
            part.Values[k] += p[i * c + k] * q[i * c + k];
          }
        }
        return part;
      });
      for (int k = 0; k < c; ++k)
      {
        alpha[k] = converged[k] ? 0.0 : rz[k] / pq.Values[k];
      }
      // x, r and z in one pass, with |r|^2 and r.z.
      sums = this->ForRanges(n, [&](Index begin, Index end) {
        Sums part(2 * c);
        for (Index i = begin; i < end; ++i)
        {
          for (int k = 0; k < c; ++k)
          {
            const Index e = i * c + k;
            X[e] += alpha[k] * p[e];
            r[e] -= alpha[k] * q[e];
            z[e] = inverseDiagonal[i] * r[e];
            part.Values[k] += r[e] * r[e];
            part.Values[c + k] += r[e] * z[e];
          }
        }
        return part;
      });
      for (int k = 0; k < c; ++k)
      {
        if (converged[k])
        {
          continue; // its direction is zeroed below
        }
        if (sums.Values[k] <= goal[k])
        {
          converged[k] = 1;
          --open;
          continue;
        }
        beta[k] = sums.Values[c + k] / rz[k];
        rz[k] = sums.Values[c + k];
      }
      if (open == 0)
      {
        break;
      }
      this->ForRanges(n, [&](Index begin, Index end) {
        for (Index i = begin; i < end; ++i)
        {
          for (int k = 0; k < c; ++k)
          {
            const Index e = i * c + k;
            p[e] = converged[k] ? 0.0 : z[e] + beta[k] * p[e];
          }
        }
        return 0.0;
      });
    }
  }
  /// Position of entry (i, k) in Values (the pattern contains it).
  Index Find(Index i, Index k) const
  {
    const Column* begin = this->Columns.data() + this->RowStart[i];
    const Column* end = this->Columns.data() + this->RowStart[i + 1];
    return static_cast<Index>(
      std::lower_bound(begin, end, static_cast<Column>(k)) - this->Columns.data());
  }
};

namespace
{
double Seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

/// The CSR pattern of the point graph of a simplicial mesh (every pair of
/// points sharing a cell, and every point with itself), from the cells
/// around each point (with ids of type Id: 32 bits when they fit, half the
/// memory); rows in concurrent tasks over point ranges when a runner is
/// given, each into a block of its own, then moved into place.
template <class Id>
void PointGraph(const MeshView& mesh, int tasks,
  const std::function<void(int, const std::function<void(int)>&)>& runTasks,
  LargeVector<Index>& start, LargeVector<Column>& columns)
{
  LargeVector<Id> cellStart;
  LargeVector<Id> cells;
  BuildPointCells(mesh, cellStart, cells);
  const int n = mesh.CornersPerCell();
  const Index points = mesh.NumberOfPoints;
  tasks = runTasks ? static_cast<int>(std::max<Index>(1, std::min<Index>(tasks, points / 4096))) : 1;
  start.assign(static_cast<size_t>(points) + 1, 0);
  // One task writes its rows straight into `columns`.
  std::vector<LargeVector<Column>> blocks(static_cast<size_t>(tasks > 1 ? tasks : 0));
  auto rows = [&](int k) {
    LargeVector<Column>& block = tasks > 1 ? blocks[k] : columns;
    block.clear();
    block.reserve(static_cast<size_t>(points / tasks + 1) * (n == 3 ? 7 : 15));
    std::vector<Column> row;
    for (Index p = points * k / tasks; p < points * (k + 1) / tasks; ++p)
    {
      row.assign(1, static_cast<Column>(p));
      for (Index i = cellStart[p]; i < cellStart[p + 1]; ++i)
      {
        const Index* ids = mesh.Cell(cells[i]);
        for (int c = 0; c < n; ++c)
        {
          row.push_back(static_cast<Column>(ids[c]));
        }
      }
      // Rows are short (7 entries in 2D, 15 in 3D on average): insertion
      // sort, unless a point has very many cells around it.
      if (row.size() > 64)
      {
        std::sort(row.begin(), row.end());
      }
      else
      {
        for (size_t i = 1; i < row.size(); ++i)
        {
          const Column v = row[i];
          size_t j = i;
          for (; j > 0 && row[j - 1] > v; --j)
          {
            row[j] = row[j - 1];
          }
          row[j] = v;
        }
      }
      const Index size = std::unique(row.begin(), row.end()) - row.begin();
      block.insert(block.end(), row.begin(), row.begin() + size);
      start[p + 1] = size;
    }
  };
  if (tasks > 1)
  {
    runTasks(tasks, rows);
  }
  else
  {
    rows(0);
  }
  for (Index p = 0; p < points; ++p)
  {
    start[p + 1] += start[p];
  }
  if (tasks > 1)
  {
    columns.resize(static_cast<size_t>(start[points]));
    runTasks(tasks, [&](int k) {
      std::copy(blocks[k].begin(), blocks[k].end(), columns.begin() + start[points * k / tasks]);
      LargeVector<Column>().swap(blocks[k]);
    });
  }
}

void PointGraph(const MeshView& mesh, int tasks,
  const std::function<void(int, const std::function<void(int)>&)>& runTasks,
  LargeVector<Index>& start, LargeVector<Column>& columns)
{
  if (mesh.NumberOfCells * mesh.CornersPerCell() < std::numeric_limits<std::int32_t>::max())
  {
    PointGraph<std::int32_t>(mesh, tasks, runTasks, start, columns);
  }
  else
  {
    PointGraph<Index>(mesh, tasks, runTasks, start, columns);
  }
}

/**
 * Receives every piece from the search: adds its local mortar integrals to
 * M_tt (per target cell, written once per cell: the searches deliver the
 * pieces of a cell one after the other), to the right-hand sides M_ts u_s of
 * the given fields, and, when kept, to M_ts itself.
 */
template <class Intersector>
struct MortarAssembler
{
  static constexpr int N = Intersector::Corners;
  using Cell = typename Intersector::Cell;

  const MortarProjector::Internals* Pattern = nullptr; ///< CSR pattern of M_tt
  double* Values = nullptr;       ///< M_tt values being summed
  double* Rhs = nullptr;          ///< target points x Components being summed
  const double* Fields = nullptr; ///< source points x Components
  int Components = 0;
  std::vector<Triplet>* Mts = nullptr;
  /// Per target cell: the covered fraction of its measure, written when
  /// its last piece has come (each cell belongs to one task).
  double* CoveredFraction = nullptr;
  double CoveredSum = 0.0; ///< measure of all pieces of this task
  Index Overcovered = 0;   ///< cells whose pieces add up to more than the cell
  IntersectionPieces* Pieces = nullptr;
  Index Count = 0;
  /**
   * With concurrent tasks: per target point, whether cells of other tasks
   * also touch it. Rows of such points are not written directly but
   * collected in Deferred / DeferredRhs (position, value) and added after
   * all tasks, in task order. Null for a single task.
   */
  const char* Shared = nullptr;
  std::vector<std::pair<Index, double>> Deferred;
  std::vector<std::pair<Index, double>> DeferredRhs;
  std::vector<double> Scratch; ///< N x Components, right-hand sides of shared points

  Index Current = -1;
  Cell CurrentCell;            ///< the target cell whose pieces are coming
  double CurrentMoments[N][N]; ///< of its pieces so far, about its corner 0

  void Flush()
  {
    if (this->Current < 0)
    {
      return;
    }
    const double covered = this->CurrentMoments[0][0];
    const double fraction = covered / this->CurrentCell.Measure;
    this->Overcovered += fraction > 1.0 + 1e-9;
    this->CoveredFraction[this->Current] = std::min(1.0, fraction);
    this->CoveredSum += covered;
    if (!(covered > 0.0))
    {
      this->Current = -1;
      return; // only touching pieces
    }
    double mtt[N][N];
    Intersector::TargetMass(this->CurrentCell, this->CurrentMoments, mtt);
    const Index* points = this->CurrentCell.Points;
    for (int i = 0; i < N; ++i)
    {
      const bool shared = this->Shared && this->Shared[points[i]];
      for (int k = 0; k < N; ++k)
      {
        const Index position = this->Pattern->Find(points[i], points[k]);
        if (shared)
        {
          this->Deferred.emplace_back(position, mtt[i][k]);
        }
        else
        {
          this->Values[position] += mtt[i][k];
        }
      }
    }
    this->Current = -1;
  }

  void operator()(const Cell& t, const Cell& s, const typename Intersector::Piece& piece)
  {
    if (t.Id != this->Current)
    {
      this->Flush();
      this->Current = t.Id;
      this->CurrentCell = t;
      for (int i = 0; i < N; ++i)
      {
        for (int k = 0; k < N; ++k)
        {
          this->CurrentMoments[i][k] = 0.0;
        }
      }
    }
    double measure;
    const int nc = this->Components;
    if (this->Mts)
    {
      double mts[N][N] = {};
      measure = Intersector::IntegrateMixed(piece, t, s, mts, this->CurrentMoments);
      if (!(measure > 0.0))
      {
        return; // the cells only touch
      }
      for (int i = 0; i < N; ++i)
      {
        const bool shared = this->Shared && this->Shared[t.Points[i]];
        double* rhs = this->Rhs + t.Points[i] * nc;
        for (int j = 0; j < N; ++j)
        {
          const double* u = this->Fields + s.Points[j] * nc;
          for (int c = 0; c < nc; ++c)
          {
            if (shared)
            {
              this->DeferredRhs.emplace_back(t.Points[i] * nc + c, mts[i][j] * u[c]);
            }
            else
            {
              rhs[c] += mts[i][j] * u[c];
            }
          }
          this->Mts->emplace_back(t.Points[i], s.Points[j], mts[i][j]);
        }
      }
    }
    else
    {
      const double* u[N];
      double* rhs[N];
      bool anyShared = false;
      for (int i = 0; i < N; ++i)
      {
        u[i] = this->Fields + s.Points[i] * nc;
        if (this->Shared && this->Shared[t.Points[i]])
        {
          anyShared = true;
          this->Scratch.assign(static_cast<size_t>(N) * nc, 0.0);
        }
      }
      for (int i = 0; i < N; ++i)
      {
        rhs[i] = (this->Shared && this->Shared[t.Points[i]]) ? this->Scratch.data() + i * nc
                                                             : this->Rhs + t.Points[i] * nc;
      }
      measure = Intersector::IntegrateField(piece, t, s, this->CurrentMoments, u, nc, rhs);
      if (!(measure > 0.0))
      {
        return; // the cells only touch
      }
      if (anyShared)
      {
        for (int i = 0; i < N; ++i)
        {
          if (this->Shared[t.Points[i]])
          {
            for (int c = 0; c < nc; ++c)
            {
              this->DeferredRhs.emplace_back(t.Points[i] * nc + c, rhs[i][c]);
            }
          }
        }
      }
    }
    ++this->Count;
    if (this->Pieces)
    {
      Intersector::Append(piece, t.Id, s.Id, measure, *this->Pieces);
    }
  }
};

bool CheckMesh(const MeshView& mesh, const char* name, bool needNeighbors, std::string& error)
{
  if (mesh.Dimension != 2 && mesh.Dimension != 3)
  {
    error = std::string(name) + ": only triangle (2D) and tetrahedron (3D) meshes are supported";
    return false;
  }
  if (mesh.NumberOfCells > 0 && (!mesh.Points || !mesh.Connectivity))
  {
    error = std::string(name) + ": missing points or connectivity";
    return false;
  }
  if (needNeighbors && mesh.NumberOfCells > std::numeric_limits<NeighborId>::max())
  {
    error = std::string(name) + " has " + std::to_string(mesh.NumberOfCells) +
      " cells; the advancing front supports at most 2^31 - 1";
    return false;
  }
  if (needNeighbors && mesh.NumberOfCells > 0 && !mesh.Neighbors)
  {
    error = std::string(name) + ": the advancing front needs cell neighbours";
    return false;
  }
  const Index n = mesh.NumberOfCells * mesh.CornersPerCell();
  for (Index i = 0; i < n; ++i)
  {
    if (mesh.Connectivity[i] < 0 || mesh.Connectivity[i] >= mesh.NumberOfPoints)
    {
      error = std::string(name) + ": a cell refers to a point that does not exist";
      return false;
    }
  }
  return true;
}
} // namespace

MortarProjector::MortarProjector()
  : Impl(new Internals)
{
}

MortarProjector::~MortarProjector() = default;

bool MortarProjector::Build(const MeshView& target, const MeshView& source,
  CandidateLocator* locator, const ProjectionOptions& options, const double* fields,
  int components)
{
  this->Impl.reset(new Internals);
  this->Statistics = SearchStatistics();
  this->Timings = ProjectionTimings();
  this->Pieces = IntersectionPieces();
  this->Error.clear();
  this->ValidPoints.assign(static_cast<size_t>(target.NumberOfPoints), 0);
  this->NumberOfValidPoints = 0;
  this->CoveredFraction.assign(static_cast<size_t>(target.NumberOfCells), 0.0);
  this->CoveredMeasure = 0;
  this->OvercoveredCells = 0;
  this->KeepsMixedMatrix = options.KeepMixedMatrix;

  const bool front = options.Method == SearchMethod::AdvancingFront;
  if (!CheckMesh(target, "Input (target)", front, this->Error) ||
    !CheckMesh(source, "Source", front, this->Error))
  {
    return false;
  }
  if (front && !locator)
  {
    this->Error = "the advancing front needs a locator over the source cells";
    return false;
  }
  if (target.Dimension != source.Dimension)
  {
    this->Error = "Input and Source have different dimensions (" +
      std::to_string(target.Dimension) + "D and " + std::to_string(source.Dimension) + "D)";
    return false;
  }
  if (components < 0 || (components > 0 && !fields))
  {
    this->Error = "fields to project: a pointer and a number of components are needed";
    return false;
  }
  if (target.NumberOfPoints > std::numeric_limits<Column>::max())
  {
    this->Error = "Input (target) has " + std::to_string(target.NumberOfPoints) +
      " points; at most 2^31 - 1 are supported";
    return false;
  }
  this->Pieces.Dimension = target.Dimension;
  if (target.Dimension == 2)
  {
    return this->Assemble<TriangleIntersector>(target, source, locator, options, fields, components);
  }
  return this->Assemble<TetrahedronIntersector>(target, source, locator, options, fields, components);
}

template <class Intersector>
bool MortarProjector::Assemble(const MeshView& target, const MeshView& source,
  CandidateLocator* locator, const ProjectionOptions& options, const double* fields,
  int components)
{
  auto start = std::chrono::steady_clock::now();
  Internals& m = *this->Impl;
  m.Tasks = std::max(1, options.Tasks);
  m.MaxIterations = std::max(0, options.MaxIterations);
  m.RunTasks = options.RunTasks;
  PointGraph(target, m.Tasks, m.RunTasks, m.RowStart, m.Columns);
  m.Values.assign(m.Columns.size(), 0.0);
  m.Components = components;
  m.Rhs.assign(static_cast<size_t>(target.NumberOfPoints) * components, 0.0);
  // The target cells in ranges, one per task, each with its own front,
  // locator and sums (a single task sums straight into the result).
  const Index cells = target.NumberOfCells;
  const int tasks = static_cast<int>(std::max<Index>(1, std::min<Index>(options.Tasks, cells / 64)));
  struct Task
  {
    MortarAssembler<Intersector> Assembler;
    std::vector<Triplet> Mts;
    IntersectionPieces Pieces;
    SearchStatistics Statistics;
    std::vector<Index> DegenerateSources;
    std::unique_ptr<CandidateLocator> Locator;
  };
  // Target points touched by the cells of more than one task: their rows
  // are summed after the tasks (see MortarAssembler::Shared).
  std::vector<char> shared;
  if (tasks > 1)
  {
    shared.assign(static_cast<size_t>(target.NumberOfPoints), 0);
    std::vector<int> owner(static_cast<size_t>(target.NumberOfPoints), -1);
    const int corners = target.CornersPerCell();
    for (int k = 0; k < tasks; ++k)
    {
      for (Index c = cells * k / tasks; c < cells * (k + 1) / tasks; ++c)
      {
        for (int i = 0; i < corners; ++i)
        {
          const Index point = target.Cell(c)[i];
          if (owner[point] < 0)
          {
            owner[point] = k;
          }
          else if (owner[point] != k)
          {
            shared[point] = 1;
          }
        }
      }
    }
  }
  std::vector<Task> work(static_cast<size_t>(tasks));
  for (int k = 0; k < tasks; ++k)
  {
    Task& w = work[k];
    MortarAssembler<Intersector>& a = w.Assembler;
    a.Pattern = &m;
    a.Values = m.Values.data();
    a.Rhs = m.Rhs.data();
    a.Shared = tasks > 1 ? shared.data() : nullptr;
    a.Fields = fields;
    a.Components = components;
    a.Mts = options.KeepMixedMatrix ? &w.Mts : nullptr;
    a.CoveredFraction = this->CoveredFraction.data();
    a.Pieces = options.KeepPieces ? (tasks > 1 ? &w.Pieces : &this->Pieces) : nullptr;
    if (locator && tasks > 1)
    {
      w.Locator = locator->NewForThread();
    }
  }
  this->Timings.Assembly = Seconds(start);

  start = std::chrono::steady_clock::now();
  auto run = [&](int k) {
    Task& w = work[k];
    const Index begin = cells * k / tasks;
    const Index end = cells * (k + 1) / tasks;
    if (options.Method == SearchMethod::AdvancingFront)
    {
      CandidateLocator& seeds = tasks > 1 ? *w.Locator : *locator;
      AdvancingFrontSearch<Intersector>(
        target, source, seeds, w.Assembler, w.Statistics, begin, end, &w.DegenerateSources);
    }
    else
    {
      BruteForceSearch<Intersector>(
        target, source, w.Assembler, w.Statistics, begin, end, &w.DegenerateSources);
    }
    w.Assembler.Flush();
  };
  if (options.RunTasks && tasks > 1)
  {
    options.RunTasks(tasks, run);
  }
  else
  {
    for (int k = 0; k < tasks; ++k)
    {
      run(k);
    }
  }
  // Sum the tasks' contributions, in task order (deterministic).
  std::vector<Triplet> mts;
  std::vector<Index> degenerateSources;
  for (Task& w : work)
  {
    for (const auto& entry : w.Assembler.Deferred)
    {
      m.Values[entry.first] += entry.second;
    }
    for (const auto& entry : w.Assembler.DeferredRhs)
    {
      m.Rhs[entry.first] += entry.second;
    }
    if (tasks > 1)
    {
      IntersectionPieces& all = this->Pieces;
      const Index shift = all.Offsets.back();
      for (size_t i = 1; i < w.Pieces.Offsets.size(); ++i)
      {
        all.Offsets.push_back(w.Pieces.Offsets[i] + shift);
      }
      all.Points.insert(all.Points.end(), w.Pieces.Points.begin(), w.Pieces.Points.end());
      all.TargetCell.insert(all.TargetCell.end(), w.Pieces.TargetCell.begin(), w.Pieces.TargetCell.end());
      all.SourceCell.insert(all.SourceCell.end(), w.Pieces.SourceCell.begin(), w.Pieces.SourceCell.end());
      all.Measure.insert(all.Measure.end(), w.Pieces.Measure.begin(), w.Pieces.Measure.end());
    }
    mts.insert(mts.end(), w.Mts.begin(), w.Mts.end());
    this->Statistics.IntersectionTests += w.Statistics.IntersectionTests;
    this->Statistics.TouchingPairs += w.Statistics.TouchingPairs;
    this->Statistics.LocatorQueries += w.Statistics.LocatorQueries;
    this->Statistics.FullLocatorQueries += w.Statistics.FullLocatorQueries;
    this->Statistics.SeedWalks += w.Statistics.SeedWalks;
    this->Statistics.WalkSteps += w.Statistics.WalkSteps;
    this->Statistics.DegenerateTargetCells += w.Statistics.DegenerateTargetCells;
    degenerateSources.insert(degenerateSources.end(), w.DegenerateSources.begin(),
      w.DegenerateSources.end());
    this->CoveredMeasure += w.Assembler.CoveredSum;
    this->OvercoveredCells += w.Assembler.Overcovered;
    this->Statistics.Pieces += w.Assembler.Count;
  }
  work.clear();
  this->Timings.Search = Seconds(start);

  start = std::chrono::steady_clock::now();
  if (options.KeepMixedMatrix)
  {
    m.Mts.resize(target.NumberOfPoints, source.NumberOfPoints);
    m.Mts.setFromTriplets(mts.begin(), mts.end());
    std::vector<Triplet>().swap(mts);
  }
  std::sort(degenerateSources.begin(), degenerateSources.end());
  this->Statistics.DegenerateSourceCells = static_cast<Index>(
    std::unique(degenerateSources.begin(), degenerateSources.end()) - degenerateSources.begin());
  // A point is valid when its support meets the source: its diagonal entry
  // of the covered mass matrix is positive. An invalid point's whole row is
  // zero (no piece touches its support); a 1 on the diagonal decouples it.
  for (Index i = 0; i < target.NumberOfPoints; ++i)
  {
    double& diagonal = m.Values[m.Find(i, i)];
    if (diagonal > 0.0)
    {
      this->ValidPoints[i] = 1;
      ++this->NumberOfValidPoints;
    }
    else
    {
      diagonal = 1.0;
    }
  }
  this->Timings.Assembly += Seconds(start);
  return true;
}

bool MortarProjector::Solve(const double* rhs, int components, double* x, double fill) const
{
  const Internals& m = *this->Impl;
  const Index n = static_cast<Index>(m.RowStart.size()) - 1;
  if (n <= 0 || components <= 0)
  {
    return true;
  }
  // The covered mass matrix is symmetric positive definite and, scaled by its
  // diagonal, well conditioned on reasonable meshes: conjugate gradients with
  // a Jacobi preconditioner to rounding level, all fields at once. Targets
  // covered only in slivers can make it ill conditioned: then a sparse
  // LDL^T factorization for the fields that did not converge.
  std::vector<char> converged;
  m.ConjugateGradients(rhs, x, components, 1e-14, m.MaxIterations, converged);
  LargeVector<double> b;
  for (int c = 0; c < components; ++c)
  {
    if (converged[c])
    {
      continue;
    }
    if (!m.Direct)
    {
      SparseMatrix matrix(n, n);
      std::vector<Triplet> entries;
      entries.reserve(m.Values.size());
      for (Index i = 0; i < n; ++i)
        for (Index p = m.RowStart[i]; p < m.RowStart[i + 1]; ++p)
          entries.emplace_back(i, m.Columns[p], m.Values[p]);
      matrix.setFromTriplets(entries.begin(), entries.end());
      m.Direct.reset(new Eigen::SimplicialLDLT<SparseMatrix>(matrix));
    }
    if (m.Direct->info() != Eigen::Success)
    {
      return false;
    }
    b.resize(static_cast<size_t>(n));
    for (Index i = 0; i < n; ++i)
    {
      b[i] = rhs[i * components + c];
    }
    const Eigen::VectorXd solution = m.Direct->solve(Eigen::Map<const Eigen::VectorXd>(b.data(), n));
    for (Index i = 0; i < n; ++i)
    {
      x[i * components + c] = solution[i];
    }
  }
  for (Index i = 0; i < n; ++i)
  {
    if (!this->ValidPoints[i])
    {
      std::fill(x + i * components, x + (i + 1) * components, fill);
    }
  }
  return true;
}

bool MortarProjector::Project(double* targetValues, double fill) const
{
  const auto start = std::chrono::steady_clock::now();
  const bool ok = this->Solve(this->Impl->Rhs.data(), this->Impl->Components, targetValues, fill);
  this->Timings.Solve = Seconds(start);
  return ok;
}

bool MortarProjector::Project(
  const double* sourceValues, int components, double* targetValues, double fill) const
{
  if (!this->KeepsMixedMatrix)
  {
    return false;
  }
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const auto& mts = this->Impl->Mts;
  Eigen::Map<const RowMajor> us(sourceValues, mts.cols(), components);
  const RowMajor rhs = mts * us;
  return this->Solve(rhs.data(), components, targetValues, fill);
}

double MortarProjector::MixedMassEntry(Index targetPoint, Index sourcePoint) const
{
  return this->KeepsMixedMatrix ? this->Impl->Mts.coeff(targetPoint, sourcePoint) : 0.0;
}

double MortarProjector::TargetMassEntry(Index targetPoint, Index otherTargetPoint) const
{
  const Internals& m = *this->Impl;
  if (!this->ValidPoints[targetPoint])
  {
    return 0.0;
  }
  const Index p = m.Find(targetPoint, otherTargetPoint);
  return (p < m.RowStart[targetPoint + 1] && m.Columns[p] == otherTargetPoint) ? m.Values[p] : 0.0;
}
} // namespace mp
