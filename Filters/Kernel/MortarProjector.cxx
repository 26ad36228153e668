// SPDX-License-Identifier: BSD-3-Clause
#include "MortarProjector.h"

#include "PairSearch.h"
#include "TetrahedronIntersector.h"
#include "TriangleIntersector.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <chrono>
#include <cmath>

namespace mp
{
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, Index>;
using Triplet = Eigen::Triplet<double, Index>;

struct MortarProjector::Internals
{
  SparseMatrix Mts; ///< target points x source points
  SparseMatrix Mtt; ///< target points x target points (covered part)
  Eigen::SimplicialLDLT<SparseMatrix> Solver; ///< on the valid rows of Mtt
  std::vector<Index> Reduced;                 ///< target point -> row of the solver, or -1
};

namespace
{
double Seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

/**
 * Collects the local mortar matrices of every piece. The searches deliver
 * the pieces of one target cell one after the other, so the target-target
 * block is summed per cell and written once per cell.
 */
template <class Intersector>
struct MortarAssembler
{
  static constexpr int N = Intersector::Corners;
  using Cell = typename Intersector::Cell;

  std::vector<Triplet> Mts;
  std::vector<Triplet> Mtt;
  std::vector<double> CoveredMeasure; ///< per target cell
  IntersectionPieces* Pieces = nullptr;
  Index Count = 0;

  Index Current = -1;
  Index CurrentPoints[N];
  double CurrentMtt[N][N];

  void Flush()
  {
    if (this->Current < 0)
    {
      return;
    }
    for (int i = 0; i < N; ++i)
    {
      for (int k = 0; k < N; ++k)
      {
        this->Mtt.emplace_back(this->CurrentPoints[i], this->CurrentPoints[k], this->CurrentMtt[i][k]);
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
      for (int i = 0; i < N; ++i)
      {
        this->CurrentPoints[i] = t.Points[i];
        for (int k = 0; k < N; ++k)
        {
          this->CurrentMtt[i][k] = 0.0;
        }
      }
    }
    double mts[N][N] = {};
    const double measure = Intersector::Integrate(piece, t, s, mts, this->CurrentMtt);
    if (!(measure > 0.0))
    {
      return; // the cells only touch
    }
    ++this->Count;
    this->CoveredMeasure[t.Id] += measure;
    for (int i = 0; i < N; ++i)
    {
      for (int j = 0; j < N; ++j)
      {
        this->Mts.emplace_back(t.Points[i], s.Points[j], mts[i][j]);
      }
    }
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
  CandidateLocator* locator, const ProjectionOptions& options)
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
  this->Pieces.Dimension = target.Dimension;
  if (target.Dimension == 2)
  {
    return this->Assemble<TriangleIntersector>(target, source, locator, options);
  }
  return this->Assemble<TetrahedronIntersector>(target, source, locator, options);
}

template <class Intersector>
bool MortarProjector::Assemble(const MeshView& target, const MeshView& source,
  CandidateLocator* locator, const ProjectionOptions& options)
{
  MortarAssembler<Intersector> assembler;
  assembler.CoveredMeasure.assign(static_cast<size_t>(target.NumberOfCells), 0.0);
  assembler.Pieces = options.KeepPieces ? &this->Pieces : nullptr;

  auto start = std::chrono::steady_clock::now();
  if (options.Method == SearchMethod::AdvancingFront)
  {
    AdvancingFrontSearch<Intersector>(target, source, *locator, assembler, this->Statistics);
  }
  else
  {
    BruteForceSearch<Intersector>(target, source, assembler, this->Statistics);
  }
  assembler.Flush();
  this->Statistics.Pieces = assembler.Count;
  this->Timings.Search = Seconds(start);

  start = std::chrono::steady_clock::now();
  const Index nt = target.NumberOfPoints;
  this->Impl->Mts.resize(nt, source.NumberOfPoints);
  this->Impl->Mts.setFromTriplets(assembler.Mts.begin(), assembler.Mts.end());
  this->Impl->Mtt.resize(nt, nt);
  this->Impl->Mtt.setFromTriplets(assembler.Mtt.begin(), assembler.Mtt.end());
  std::vector<Triplet>().swap(assembler.Mts);

  typename Intersector::Cell cell;
  for (Index c = 0; c < source.NumberOfCells; ++c)
  {
    this->Statistics.DegenerateSourceCells += !Intersector::Prepare(source, c, cell);
  }
  for (Index c = 0; c < target.NumberOfCells; ++c)
  {
    this->CoveredMeasure += assembler.CoveredMeasure[c];
    if (!Intersector::Prepare(target, c, cell))
    {
      ++this->Statistics.DegenerateTargetCells;
    }
    else
    {
      const double fraction = assembler.CoveredMeasure[c] / cell.Measure;
      this->OvercoveredCells += fraction > 1.0 + 1e-9;
      this->CoveredFraction[c] = std::min(1.0, fraction);
    }
  }
  // A point is valid when its support meets the source: its diagonal entry
  // of the covered mass matrix is positive.
  auto& reduced = this->Impl->Reduced;
  reduced.assign(static_cast<size_t>(nt), -1);
  for (Index i = 0; i < nt; ++i)
  {
    if (this->Impl->Mtt.coeff(i, i) > 0.0)
    {
      this->ValidPoints[i] = 1;
      reduced[i] = this->NumberOfValidPoints++;
    }
  }
  std::vector<Triplet> valid;
  valid.reserve(assembler.Mtt.size());
  for (const Triplet& e : assembler.Mtt)
  {
    if (reduced[e.row()] >= 0 && reduced[e.col()] >= 0)
    {
      valid.emplace_back(reduced[e.row()], reduced[e.col()], e.value());
    }
  }
  std::vector<Triplet>().swap(assembler.Mtt);
  SparseMatrix mtt(this->NumberOfValidPoints, this->NumberOfValidPoints);
  mtt.setFromTriplets(valid.begin(), valid.end());
  this->Timings.Assembly = Seconds(start);

  start = std::chrono::steady_clock::now();
  if (this->NumberOfValidPoints > 0)
  {
    this->Impl->Solver.compute(mtt);
    if (this->Impl->Solver.info() != Eigen::Success)
    {
      this->Error = "the mass matrix of the covered target part could not be factorized";
      return false;
    }
  }
  this->Timings.Factorization = Seconds(start);
  return true;
}

void MortarProjector::Project(
  const double* sourceValues, int components, double* targetValues, double fill) const
{
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Index ns = this->Impl->Mts.cols();
  const Index nt = this->Impl->Mts.rows();
  Eigen::Map<const RowMajor> us(sourceValues, ns, components);
  Eigen::Map<RowMajor> ut(targetValues, nt, components);
  if (this->NumberOfValidPoints == 0)
  {
    ut.setConstant(fill);
    return;
  }
  const Eigen::MatrixXd rhs = this->Impl->Mts * us;
  Eigen::MatrixXd reducedRhs(this->NumberOfValidPoints, components);
  for (Index i = 0; i < nt; ++i)
  {
    if (this->Impl->Reduced[i] >= 0)
    {
      reducedRhs.row(this->Impl->Reduced[i]) = rhs.row(i);
    }
  }
  const Eigen::MatrixXd solution = this->Impl->Solver.solve(reducedRhs);
  for (Index i = 0; i < nt; ++i)
  {
    const Index r = this->Impl->Reduced[i];
    if (r >= 0)
    {
      ut.row(i) = solution.row(r);
    }
    else
    {
      ut.row(i).setConstant(fill);
    }
  }
}

double MortarProjector::MixedMassEntry(Index targetPoint, Index sourcePoint) const
{
  return this->Impl->Mts.coeff(targetPoint, sourcePoint);
}

double MortarProjector::TargetMassEntry(Index targetPoint, Index otherTargetPoint) const
{
  return this->Impl->Mtt.coeff(targetPoint, otherTargetPoint);
}
} // namespace mp
