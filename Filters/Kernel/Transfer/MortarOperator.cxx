// SPDX-License-Identifier: BSD-3-Clause
// MortarOperator (MortarOperator.h): the checks of the input, the build's
// entry and its last stage (M_tt, the valid functions, the solver), and
// what is read or given back once built. The other stages: the shared
// search in MortarBuild.cxx (with MortarSession.h), the projection of
// fields in MortarApply.cxx.
#include "Transfer/MortarOperator.h"

#include "Geometry/Intersectors.h"
#include "Geometry/Measures.h"
#include "Mesh/NodalCells.h"
#include "Search/ParallelSearch.h"
#include "Transfer/MassMatrix.h"
#include "Transfer/NodalMass.h"
#include "Transfer/NodalSpace.h"
#include "Transfer/StageClock.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

namespace mp
{
namespace
{
/// How many of ids[0..n) lie outside [0, bound), counted in `runner`'s tasks.
template <class Id>
Index CountOutside(const Id* ids, Index n, Index bound, const TaskRunner& runner)
{
  return runner.ForRanges(
    n,
    [=](Index begin, Index end) {
      Index outside = 0;
      for (Index i = begin; i < end; ++i)
      {
        // (A negative id is a huge unsigned one.)
        outside += static_cast<std::uint64_t>(ids[i]) >= static_cast<std::uint64_t>(bound);
      }
      return outside;
    },
    Index(1) << 16);
}

std::string CheckIds(const MeshView& mesh, const char* name, const TaskRunner& runner)
{
  const Index uses = mesh.NumberOfCells * mesh.CornersPerCell();
  if ((mesh.Connectivity32 ? CountOutside(mesh.Connectivity32, uses, mesh.AllPoints(), runner)
                           : CountOutside(mesh.Connectivity, uses, mesh.AllPoints(), runner)) > 0)
  {
    return std::string(name) + ": a cell refers to a point that does not exist";
  }
  if (mesh.Parent &&
    CountOutside(mesh.Parent, mesh.NumberOfCells, mesh.NumberOfParents, runner) > 0)
  {
    return std::string(name) + ": a cell's parent does not exist";
  }
  return std::string();
}
} // namespace

MortarOperator::MortarOperator() = default;
MortarOperator::~MortarOperator() = default;

bool MortarOperator::Build(const MeshView& target, const MeshView& source,
  CandidateLocator* locator, const OperatorOptions& options)
{
  return BuildTogether({ this }, { options }, target, source, locator);
}

bool MortarOperator::Check(
  const MeshView& target, const MeshView& source, CandidateLocator* locator)
{
  const OperatorOptions& options = this->Options;
  for (const auto& mesh :
    { std::make_pair(&target, "Input (target)"), std::make_pair(&source, "Source") })
  {
    const MeshView& m = *mesh.first;
    if (!(((m.CellDimension == 2 || m.CellDimension == 3) && m.IsVolumeMesh()) ||
          m.IsSurfaceMesh() || m.IsCurveMesh()))
    {
      this->Error = std::string(mesh.second) +
        ": only segments of curves (in the plane or in space), triangles in the plane (2D), "
        "triangles of surfaces in 3D and tetrahedra in space (3D) have a geometry";
      return false;
    }
    this->Error = CheckSearchMesh(m, mesh.second, options.Method);
    if (this->Error.empty())
    {
      this->Error = CheckIds(m, mesh.second, options.Runner);
    }
    if (this->Error.empty())
    {
      this->Error = CheckNodalCells(m, mesh.second);
    }
    if (!this->Error.empty())
    {
      return false;
    }
  }
  if (SearchNeedsNeighbors(options.Method) && !locator)
  {
    this->Error = "the advancing front needs a locator over the source cells";
    return false;
  }
  const bool trace = IsTracePair(target, source);
  if (target.CellDimension == 2 && source.CellDimension == 2 &&
    target.SpaceDimension != source.SpaceDimension)
  {
    this->Error = "Input and Source are triangles seen in different spaces (" +
      std::to_string(target.SpaceDimension) + "D and " + std::to_string(source.SpaceDimension) +
      "D): a surface in 3D is matched with a surface in 3D";
    return false;
  }
  if (target.CellDimension != source.CellDimension && !trace)
  {
    this->Error = "Input and Source have different dimensions (" +
      std::to_string(target.CellDimension) + "D and " + std::to_string(source.CellDimension) +
      "D); of different dimensions, only a surface in tetrahedra or a curve in triangles (in "
      "their plane) or tetrahedra (a trace) can be projected";
    return false;
  }
  if (options.TargetSpace == SpaceType::DP1)
  {
    this->Error = "DP1 is a source space only (reconstructed cell data): the target is P1 or P0";
    return false;
  }
  const Index rows = SpaceSize(options.TargetSpace, target);
  const Index columns = SpaceSize(options.SourceSpace, source);
  this->SourceFunctions = columns;
  if (options.FieldComponents < 0 || (options.FieldComponents > 0 && !options.Fields))
  {
    this->Error = "fields to project: a pointer and a number of components are needed";
    return false;
  }
  if (std::max(rows, columns) > std::numeric_limits<Column>::max())
  {
    this->Error = "a space of " + std::to_string(std::max(rows, columns)) +
      " functions; at most 2^31 - 1 are supported";
    return false;
  }
  return true;
}

void MortarOperator::CompleteTargetMass(const MeshView& target)
{
  if (!this->MassPending)
  {
    return;
  }
  this->MassPending = false;
  auto start = std::chrono::steady_clock::now();
  const TaskRunner& runner = this->Options.Runner;
  // The point cover (the largest covered fraction around each point) is
  // made with M_tt, from the parents' fractions: each cell's through its
  // parent (an array of fractions per kernel cell kept beside them for it
  // was 8 MiB more at the peak for a target of 10^6 cells).
  if (target.Parent)
  {
    // Split or renumbered cells: the covered fraction of each original cell
    // (here rather than right after the search: with DeferTargetMass the
    // Source's arrays are gone by now, and the two arrays of fractions take
    // no room from the search's).
    this->CoveredFraction = ParentFractions(target, this->CoveredFraction, runner);
  }
  CellValues coverFrom;
  if (this->CoveredFraction.size() >= static_cast<size_t>(target.Parents()))
  {
    coverFrom.Values = this->CoveredFraction.data();
    coverFrom.ByParent = target.Parent != nullptr;
  }
  if (this->NodalPath)
  {
    // The cells' own space: M_tt summed from the pieces' blocks (NodalMass.h).
    AssembleNodalTargetMass(this->NodalMassBlocks, target, this->Options.TargetSpace, runner,
      this->TargetMass, this->Options.TargetSpace == SpaceType::P1 ? coverFrom.Values : nullptr,
      &this->PointCover);
    std::vector<MixedBlocks>().swap(this->NodalMassBlocks);
    if (this->NodalTarget && BernsteinForm::Covers(target))
    {
      this->Bernstein.Build(target); // lumped and bounded Applies (MassType::Lumped)
    }
  }
  else
  {
    AssembleTargetMass(this->Options.TargetSpace, target, &this->Masses, runner, this->TargetMass,
      coverFrom, &this->PointCover);
  }
  this->Masses = CellMasses();
  // A function is valid when its support meets the source: its diagonal
  // entry of the covered mass matrix is positive. An invalid function's
  // whole row is zero (no piece touches its support); a 1 on the diagonal
  // decouples it.
  const Index rows = this->TargetMass.Rows;
  CsrMatrix& mass = this->TargetMass;
  this->Valid.resize(static_cast<size_t>(rows));
  this->RowSums.resize(static_cast<size_t>(rows));
  this->NumberOfValid += runner.ForRanges(
    rows,
    [&](Index begin, Index end) {
      Index valid = 0;
      for (Index i = begin; i < end; ++i)
      {
        double& diagonal = mass.Values[mass.Find(i, i)];
        const bool isValid = diagonal > 0.0;
        double sum = 0.0;
        if (isValid)
        {
          ++valid;
          for (Index p = mass.RowStart[i]; p < mass.RowStart[i + 1]; ++p)
          {
            sum += mass.Values[p];
          }
        }
        else
        {
          diagonal = 1.0;
        }
        this->Valid[i] = isValid ? 1 : 0;
        this->RowSums[i] = sum;
      }
      return valid;
    },
    16384);
  // (Its lumped start reads the valid rows' sums just made: an invalid
  // row's decoupling 1 is left out, but its right-hand side is 0.)
  this->Solver.reset(
    new BlockCG(this->TargetMass, runner, this->RowSums.data(), !this->NodalTarget));
  this->Timings.Assembly += SecondsSince(start);
}

void MortarOperator::ShareValidity(const SolverHooks& hooks)
{
  if (!hooks.Exchange)
  {
    return;
  }
  const Index n = this->TargetMass.Rows;
  std::vector<double> diagonal(static_cast<size_t>(n), 0.0);
  for (Index i = 0; i < n; ++i)
  {
    diagonal[i] = this->Valid[i] ? this->TargetMass.Values[this->TargetMass.Find(i, i)] : 0.0;
  }
  hooks.Exchange(diagonal.data(), 1);
  this->NumberOfValid = 0;
  for (Index i = 0; i < n; ++i)
  {
    if (!this->Valid[i] && diagonal[i] > 0.0)
    {
      // Covered in another part only: this part's row is empty (the 1 that
      // decoupled it goes), the other parts complete it.
      this->Valid[i] = 1;
      this->TargetMass.Values[this->TargetMass.Find(i, i)] = 0.0;
    }
    this->NumberOfValid += this->Valid[i];
  }
}

double MortarOperator::FitCoveragePower(const MeshView& target) const
{
  const bool linearVolume = !this->NodalTarget && target.IsVolumeMesh();
  return linearVolume && this->Options.SourceSpace == SpaceType::P1 ? FringeCoveragePower : 0.0;
}

bool MortarOperator::CellDataFringe(const MeshView& target) const
{
  return !this->NodalTarget && target.IsVolumeMesh() && this->Options.SourceSpace == SpaceType::P0;
}

double MortarOperator::FitAmplification(const MeshView& target) const
{
  return this->CellDataFringe(target) ? FringeCellDataAmplification : 0.0;
}

Index MortarOperator::AggregateFringe(
  const MeshView& target, double threshold, const SolverHooks& hooks, const FringeHalo* halo)
{
  if (this->FringeDone || this->Options.TargetSpace != SpaceType::P1 || !(threshold > 0.0) ||
    !this->Solver)
  {
    return this->Fringe.Count;
  }
  this->FringeDone = true;
  if (this->CellDataFringe(target))
  {
    threshold = std::max(threshold, FringeCellDataThreshold);
  }
  const auto start = std::chrono::steady_clock::now();
  const Index n = this->TargetMass.Rows;
  // The covered fraction of each function's support (on a distributed
  // system both integrals summed over the parts, so that every part decides
  // alike).
  std::vector<double> covered(this->RowSums);
  LargeVector<double> whole;
  if (this->NodalTarget)
  {
    // Second-order functions' integrals are no measure of their support
    // (NodalMass.h): its cells' covered measure instead.
    NodalSupportCover(target, this->CoveredFraction.data(), covered, whole);
  }
  else
  {
    whole = SupportIntegrals(target);
  }
  whole.resize(static_cast<size_t>(n), 0.0);
  if (hooks.Exchange)
  {
    hooks.Exchange(covered.data(), 1);
    hooks.Exchange(whole.data(), 1);
  }
  std::vector<double> fraction(static_cast<size_t>(n), 0.0);
  for (Index i = 0; i < n; ++i)
  {
    fraction[i] = whole[i] > 0.0 ? covered[i] / whole[i] : 0.0;
  }
  if (halo && halo->Hooks.Exchange)
  {
    this->AggregateWithHalo(target, fraction, threshold, *halo);
  }
  else
  {
    // One part (or a distributed system without a halo: each part then
    // extends from its own points, a shared function taking on each part
    // that part's side's extension; the sum of the parts' P^T M P is still
    // symmetric, positive definite on the free functions and exact for
    // linear fields).
    this->Fringe = ExtendFringe(target, this->Valid, fraction, threshold,
      FringeDropFractionOf(target), this->Options.Runner, false, this->FitCoveragePower(target),
      this->FitAmplification(target));
    if (this->Fringe.Count + this->Fringe.Stranded > 0)
    {
      this->FringeMass = AggregatedMass(this->TargetMass, this->Fringe, this->Options.Runner);
      this->FringeSolver.reset(
        new BlockCG(this->FringeMass, this->Options.Runner, nullptr, !this->NodalTarget));
      this->DropFringe(nullptr);
      this->FringeSystem = true;
    }
    else
    {
      this->Fringe = FringeExtension();
    }
  }
  this->Timings.Assembly += SecondsSince(start);
  return this->Fringe.Count;
}

struct MortarOperator::HaloMesh
{
  std::vector<double> Points;
  std::vector<Index> Cells;
  std::vector<Index> Parent;
  std::vector<NodalType> Types;
  std::vector<long long> Offsets;
  std::vector<long long> Nodes;
  NodalCells Nodal;
};

MeshView MortarOperator::WithHalo(const MeshView& target, const FringeHalo& halo, HaloMesh& storage)
{
  const int corners = target.CornersPerCell();
  std::vector<double>& points = storage.Points;
  std::vector<Index>& cells = storage.Cells;
  points.assign(target.Points, target.Points + 3 * target.NumberOfPoints);
  points.insert(points.end(), halo.Points.begin(), halo.Points.end());
  // Geometric-only points (curved cells split finer) after the halo's,
  // which are numbered as functions after the target's: the target's, then
  // the halo's.
  const Index functions = static_cast<Index>(points.size() / 3);
  points.insert(points.end(), target.Points + 3 * target.NumberOfPoints,
    target.Points + 3 * target.AllPoints());
  points.insert(points.end(), halo.Geometric.begin(), halo.Geometric.end());
  cells.clear();
  cells.reserve(static_cast<size_t>(target.NumberOfCells * corners) + halo.Cells.size());
  for (Index c = 0; c < target.NumberOfCells; ++c)
  {
    const CellCorners cell = target.Cell(c);
    for (int a = 0; a < corners; ++a)
    {
      cells.push_back(
        target.HasFunction(cell[a]) ? cell[a] : functions + (cell[a] - target.NumberOfPoints));
    }
  }
  for (Index k : halo.Cells)
  {
    cells.push_back(k < functions ? k : k + target.GeometricPoints);
  }
  MeshView whole;
  whole.CellDimension = target.CellDimension;
  whole.SpaceDimension = target.SpaceDimension;
  whole.Points = points.data();
  whole.NumberOfPoints = functions;
  whole.GeometricPoints = target.GeometricPoints + static_cast<Index>(halo.Geometric.size() / 3);
  whole.Connectivity = cells.data();
  whole.NumberOfCells = static_cast<Index>(cells.size()) / corners;
  const Index ghostCells = static_cast<Index>(halo.Cells.size()) / corners;
  if (target.Nodal && static_cast<Index>(halo.CellParents.size()) == ghostCells)
  {
    // The second-order parents too, the halo's after this part's, so that
    // the fringe's root cells are the whole target's (FringeRoots.h).
    const Index own = target.Parents();
    storage.Parent.resize(static_cast<size_t>(whole.NumberOfCells));
    for (Index c = 0; c < target.NumberOfCells; ++c)
    {
      storage.Parent[static_cast<size_t>(c)] = target.ParentOf(c);
    }
    for (Index g = 0; g < ghostCells; ++g)
    {
      storage.Parent[static_cast<size_t>(target.NumberOfCells + g)] =
        own + halo.CellParents[static_cast<size_t>(g)];
    }
    storage.Types.assign(target.Nodal->Type, target.Nodal->Type + own);
    storage.Types.insert(storage.Types.end(), halo.ParentTypes.begin(), halo.ParentTypes.end());
    storage.Offsets.assign(target.Nodal->Offsets, target.Nodal->Offsets + own + 1);
    storage.Nodes.assign(target.Nodal->Nodes, target.Nodal->Nodes + storage.Offsets.back());
    for (size_t q = 1; q < halo.ParentOffsets.size(); ++q)
    {
      storage.Offsets.push_back(
        storage.Offsets.back() + halo.ParentOffsets[q] - halo.ParentOffsets[q - 1]);
    }
    storage.Nodes.insert(storage.Nodes.end(), halo.ParentNodes.begin(), halo.ParentNodes.end());
    storage.Nodal.Type = storage.Types.data();
    storage.Nodal.Offsets = storage.Offsets.data();
    storage.Nodal.Nodes = storage.Nodes.data();
    whole.Parent = storage.Parent.data();
    whole.NumberOfParents = static_cast<Index>(storage.Types.size());
    whole.Nodal = &storage.Nodal;
  }
  return whole;
}

void MortarOperator::AggregateWithHalo(const MeshView& target, const std::vector<double>& fraction,
  double threshold, const FringeHalo& halo)
{
  // The serial stencil of a point depends only on the rings around it in
  // the whole target (FringeSearchRings of them): their coordinates and
  // which of their points are usable (valid and well covered, the same on
  // every part once the integrals are summed). The halo holds the other
  // parts' cells within those rings, so P's rows here are the serial ones,
  // and the same on every part that has the point; a stencil may then hold ghost points,
  // and P^T M P rows of them (the halo's hooks sum these with the parts
  // that have the points).
  const Index n = this->TargetMass.Rows;
  const Index ghosts = halo.NumberOfPoints();
  const Index rows = n + ghosts;
  const SolverHooks& extended = halo.Hooks;
  // A ghost point's covered fraction when it is usable, else 0: its
  // owner's (the only one counted; the stencils' fits weigh their points
  // by it, FringeFits.h).
  std::vector<double> usable(static_cast<size_t>(rows), 0.0);
  for (Index i = 0; i < n; ++i)
  {
    const bool counted = !extended.Counted || extended.Counted[i];
    usable[i] = counted && this->Valid[i] && fraction[i] >= threshold ? fraction[i] : 0.0;
  }
  extended.Exchange(usable.data(), 1);
  std::vector<char> valid(this->Valid);
  std::vector<double> extendedFraction(fraction);
  valid.resize(static_cast<size_t>(rows), 0);
  extendedFraction.resize(static_cast<size_t>(rows), 0.0);
  for (Index g = n; g < rows; ++g)
  {
    // Usable ghosts with their owner's fraction (at least the threshold),
    // the others invalid: none is aggregated here.
    valid[g] = usable[g] > 0.0;
    extendedFraction[g] = usable[g];
  }
  HaloMesh storage;
  const MeshView whole = WithHalo(target, halo, storage);
  // (P's rows nearest first: a point's extension, summed in that order,
  // is then the same bits on every part that has it.)
  this->Fringe =
    ExtendFringe(whole, valid, extendedFraction, threshold, FringeDropFractionOf(target),
      this->Options.Runner, true, this->FitCoveragePower(target), this->FitAmplification(target));
  // One system for all parts: aggregated when any part aggregates.
  double count = static_cast<double>(this->Fringe.Count + this->Fringe.Stranded);
  extended.Reduce(&count, 1);
  if (!(count > 0.0))
  {
    this->Fringe = FringeExtension();
    return;
  }
  if (this->Fringe.P.Rows == 0)
  {
    // Nothing aggregated in this part: P is the identity (ExtendFringe
    // leaves it empty), its share of the system M_tt's.
    this->Fringe.P = CsrMatrix::Identity(rows);
  }
  // M_tt with empty rows for the ghosts (only the stencils reach them).
  CsrMatrix padded(this->TargetMass);
  padded.Rows = padded.Columns = rows;
  padded.RowStart.resize(static_cast<size_t>(rows) + 1, padded.RowStart.back());
  this->FringeMass = AggregatedMass(padded, this->Fringe, this->Options.Runner);
  this->FringeSolver.reset(
    new BlockCG(this->FringeMass, this->Options.Runner, nullptr, !this->NodalTarget));
  this->HaloPoints = ghosts;
  this->FringeSystem = true;
  this->DropFringe(&extended);
}

void MortarOperator::DropFringe(const SolverHooks* haloHooks)
{
  // A dropped function's covered integral goes to its stencil by its
  // weights (P^T on the row sums): sum_i RowSums_i u_i over the valid
  // functions stays the integral of u = P u_free over the covered part. A
  // stranded one (no stencil: its row of P is its own) hands on nothing.
  // With a halo, the shares are summed over the extended rows and each
  // point's total added on the part that counts it (the row sums are each
  // part's own share of a shared row: their sum over the parts counts).
  const CsrMatrix& P = this->Fringe.P;
  const Index n = this->TargetMass.Rows;
  this->FringeValid = this->Valid;
  this->FringeRowSums = this->RowSums;
  this->FringeDropped = 0;
  std::vector<double> shares(haloHooks ? static_cast<size_t>(P.Rows) : 0, 0.0);
  for (Index i = 0; i < n; ++i)
  {
    if (!this->Fringe.Dropped[i])
    {
      continue;
    }
    for (Index q = P.RowStart[i]; this->Fringe.Aggregated[i] && q < P.RowStart[i + 1]; ++q)
    {
      (haloHooks ? shares[P.ColumnIndex[q]] : this->FringeRowSums[P.ColumnIndex[q]]) +=
        P.Values[q] * this->RowSums[i];
    }
    this->FringeRowSums[i] = 0.0;
    this->FringeValid[i] = 0;
    ++this->FringeDropped;
  }
  if (haloHooks)
  {
    haloHooks->Exchange(shares.data(), 1);
    for (Index i = 0; i < n; ++i)
    {
      if (!haloHooks->Counted || haloHooks->Counted[i])
      {
        this->FringeRowSums[i] += shares[i];
      }
    }
  }
}

void MortarOperator::ReleaseMatrices()
{
  this->Solver.reset();
  this->FringeSolver.reset();
  this->FringeMass = CsrMatrix();
  for (CsrMatrix* m : { &this->TargetMass, &this->MixedMass })
  {
    CsrMatrix empty;
    empty.Rows = m->Rows;
    empty.Columns = m->Columns;
    *m = std::move(empty);
  }
  UninitializedLargeVector<double>().swap(this->Rhs);
  this->Bernstein = BernsteinForm();
}

size_t MortarOperator::MemoryBytes() const
{
  auto csr = [](const CsrMatrix& m) {
    return m.RowStart.capacity() * sizeof(Index) + m.ColumnIndex.capacity() * sizeof(Column) +
      m.Values.capacity() * sizeof(double);
  };
  return csr(this->TargetMass) + csr(this->MixedMass) + csr(this->FringeMass) +
    csr(this->Fringe.P) + this->Rhs.capacity() * sizeof(double) + this->Valid.capacity() +
    this->RowSums.capacity() * sizeof(double) + this->CoveredFraction.capacity() * sizeof(double) +
    this->PointCover.capacity() * sizeof(double) + this->Pieces.MemoryBytes() +
    this->Bernstein.MemoryBytes();
}
} // namespace mp
