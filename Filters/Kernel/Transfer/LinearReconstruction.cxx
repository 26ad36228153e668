// SPDX-License-Identifier: BSD-3-Clause
#include "Transfer/LinearReconstruction.h"

#include "Mesh/CellNeighbors.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mp
{
namespace
{
/// The edges x_a - x_0 of simplex c (zero third coordinate in 2D).
void SimplexEdges(const MeshView& mesh, Index c, double (&edges)[3][3])
{
  const CellCorners corners = mesh.Cell(c);
  const double* x0 = mesh.Point(corners[0]);
  for (int a = 0; a < mesh.CellDimension; ++a)
  {
    const double* x = mesh.Point(corners[a + 1]);
    for (int i = 0; i < 3; ++i)
    {
      edges[a][i] = i < mesh.SpaceDimension ? x[i] - x0[i] : 0.0;
    }
  }
}

/// The measure of a simplex of any dimension in the plane or in space:
/// sqrt(det(E^T E)) / m! over its m edges E.
double SimplexMeasure(const MeshView& mesh, Index c)
{
  double e[3][3];
  SimplexEdges(mesh, c, e);
  const int m = mesh.CellDimension;
  if (m == 2 && mesh.SpaceDimension == 2)
  {
    return 0.5 * std::fabs(e[0][0] * e[1][1] - e[0][1] * e[1][0]);
  }
  if (m == 3)
  {
    return std::fabs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
             e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
             e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
      6.0;
  }
  Eigen::Matrix3d gram = Eigen::Matrix3d::Identity();
  for (int a = 0; a < m; ++a)
  {
    for (int b = 0; b < m; ++b)
    {
      gram(a, b) = e[a][0] * e[b][0] + e[a][1] * e[b][1] + e[a][2] * e[b][2];
    }
  }
  const double factorial = m == 3 ? 6.0 : (m == 2 ? 2.0 : 1.0);
  return std::sqrt(std::max(0.0, gram.determinant())) / factorial;
}

/// An orthonormal frame (m rows) of simplex c's plane or line, by
/// Gram-Schmidt on its edges; false when the simplex is degenerate.
bool SimplexFrame(const MeshView& mesh, Index c, double* frame)
{
  double e[3][3];
  SimplexEdges(mesh, c, e);
  for (int a = 0; a < mesh.CellDimension; ++a)
  {
    double v[3] = { e[a][0], e[a][1], e[a][2] };
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int b = 0; b < a; ++b)
    {
      const double* t = frame + 3 * b;
      const double dot = v[0] * t[0] + v[1] * t[1] + v[2] * t[2];
      for (int i = 0; i < 3; ++i)
      {
        v[i] -= dot * t[i];
      }
    }
    const double rest = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(rest > 1e-12 * length))
    {
      return false;
    }
    for (int i = 0; i < 3; ++i)
    {
      frame[3 * a + i] = v[i] / rest;
    }
  }
  return true;
}

/**
 * Whether the normal matrix A (of neighbours' offsets of unit length
 * weight) spans all M directions well: its Cholesky factor's smallest
 * pivot, squared, at least `fraction` of its trace (a direction holding
 * that share of the neighbours' weight).
 */
template <int M>
bool SpansWell(const Eigen::Matrix<double, M, M>& a, double fraction)
{
  const double scale = a.trace();
  if (!(scale > 0.0))
  {
    return false;
  }
  Eigen::LLT<Eigen::Matrix<double, M, M>> llt(a);
  if (llt.info() != Eigen::Success)
  {
    return false;
  }
  const double smallest = llt.matrixLLT().diagonal().minCoeff();
  return smallest * smallest > fraction * scale;
}

/**
 * The least-squares normal matrix A's (least-norm) inverse: A^-1 when the
 * neighbours span all M directions, else the pseudo-inverse without the
 * directions they leave (nearly) open.
 */
template <int M>
Eigen::Matrix<double, M, M> LeastNormInverse(const Eigen::Matrix<double, M, M>& a)
{
  using Matrix = Eigen::Matrix<double, M, M>;
  const double scale = a.trace();
  if (!(scale > 0.0))
  {
    return Matrix::Zero();
  }
  if (SpansWell<M>(a, 1e-10))
  {
    return a.inverse();
  }
  Eigen::SelfAdjointEigenSolver<Matrix> eigen(a);
  Matrix inverse = Matrix::Zero();
  for (int k = 0; k < M; ++k)
  {
    const double lambda = eigen.eigenvalues()(k);
    if (lambda > 1e-10 * scale)
    {
      const auto v = eigen.eigenvectors().col(k);
      inverse += (v * v.transpose()) / lambda;
    }
  }
  return inverse;
}

/// The Barth-Jespersen factor of one corner: how much of the change
/// `delta` from the cell's value `u` keeps the corner within [low, high].
inline double LimiterFactor(double u, double delta, double low, double high)
{
  if (delta > 0.0)
  {
    return std::min(1.0, (high - u) / delta);
  }
  if (delta < 0.0)
  {
    return std::min(1.0, (low - u) / delta);
  }
  return 1.0;
}
} // namespace

void LinearReconstruction::Prepare(const MeshView& mesh, const TaskRunner& runner)
{
  this->Mesh = &mesh;
  this->GroupSimplices();
  this->MeasureParents(runner);
  // The face table by point ids (the mesh's own when it has one), then the
  // sites; where copies of points were joined, the table again on the sites.
  std::vector<NeighborId> built;
  const NeighborId* across = mesh.Neighbors;
  if (!across)
  {
    MeshView own = mesh;
    own.Around = nullptr;
    built.assign(static_cast<size_t>(mesh.NumberOfCells * mesh.CornersPerCell()), -1);
    BuildFaceNeighbors(own, built.data(), runner);
    across = built.data();
  }
  this->FindSites(across);
  if (this->JoinCopies)
  {
    this->MatchFacesOnSites(runner, built);
    across = built.data();
  }
  this->GatherAroundSites(runner);
  this->FindFaceNeighbors(across, runner);
}

void LinearReconstruction::GroupSimplices()
{
  // Slots: the parents in the order of their first simplex, so that a
  // parent's neighbours, numbered alike, lie near it in memory whatever the
  // dataset's numbering (the kernel's cells are in space order). Then a
  // counting sort of the simplices by slot.
  const MeshView& mesh = *this->Mesh;
  const Index parents = mesh.Parents();
  const Index cells = mesh.NumberOfCells;
  this->SlotOf.assign(static_cast<size_t>(parents), -1);
  this->ParentOfSlot.resize(static_cast<size_t>(parents));
  Index slots = 0;
  for (Index c = 0; c < cells; ++c)
  {
    Index& slot = this->SlotOf[mesh.ParentOf(c)];
    if (slot < 0)
    {
      slot = slots;
      this->ParentOfSlot[slots++] = mesh.ParentOf(c);
    }
  }
  for (Index p = 0; p < parents; ++p)
  {
    if (this->SlotOf[p] < 0) // (a parent without simplices: last)
    {
      this->SlotOf[p] = slots;
      this->ParentOfSlot[slots++] = p;
    }
  }
  this->SlotsAreParents = true;
  for (Index p = 0; p < parents && this->SlotsAreParents; ++p)
  {
    this->SlotsAreParents = this->SlotOf[p] == p;
  }
  this->SimplexStart.assign(static_cast<size_t>(parents) + 1, 0);
  for (Index c = 0; c < cells; ++c)
  {
    ++this->SimplexStart[static_cast<size_t>(this->SlotOf[mesh.ParentOf(c)]) + 1];
  }
  for (Index p = 0; p < parents; ++p)
  {
    this->SimplexStart[p + 1] += this->SimplexStart[p];
  }
  this->Simplices.resize(static_cast<size_t>(cells));
  std::vector<Index> next(this->SimplexStart.begin(), this->SimplexStart.end() - 1);
  for (Index c = 0; c < cells; ++c)
  {
    this->Simplices[next[this->SlotOf[mesh.ParentOf(c)]]++] = c;
  }
}

void LinearReconstruction::MeasureParents(const TaskRunner& runner)
{
  const MeshView& mesh = *this->Mesh;
  const Index parents = mesh.Parents();
  const int corners = mesh.CornersPerCell();
  const bool framed = !mesh.IsVolumeMesh();
  this->Centroids.assign(3 * static_cast<size_t>(parents), 0.0);
  this->Flat.assign(static_cast<size_t>(parents), 0);
  this->Frames.assign(framed ? 3 * static_cast<size_t>(mesh.CellDimension) * parents : 0, 0.0);
  runner.ForRanges(parents, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p)
    {
      double sum[3] = { 0.0, 0.0, 0.0 };
      double measure = 0.0;
      bool hasFrame = !framed;
      for (Index i = this->SimplexStart[p]; i < this->SimplexStart[p + 1]; ++i)
      {
        const Index c = this->Simplices[i];
        const double v = SimplexMeasure(mesh, c);
        const CellCorners ids = mesh.Cell(c);
        for (int k = 0; k < corners; ++k)
        {
          const double* x = mesh.Point(ids[k]);
          for (int a = 0; a < mesh.SpaceDimension; ++a)
          {
            sum[a] += v * x[a] / corners;
          }
        }
        measure += v;
        if (!hasFrame)
        {
          hasFrame = SimplexFrame(mesh, c, &this->Frames[3 * mesh.CellDimension * static_cast<size_t>(p)]);
        }
      }
      this->Flat[p] = !(measure > 0.0);
      if (this->Flat[p])
      {
        // (No part of any integral: a neighbour of none, its centroid the
        // corners' mean for its own, unread, gradient.)
        std::fill(sum, sum + 3, 0.0);
        Index n = 0;
        for (Index i = this->SimplexStart[p]; i < this->SimplexStart[p + 1]; ++i, ++n)
        {
          const CellCorners ids = mesh.Cell(this->Simplices[i]);
          for (int k = 0; k < corners; ++k)
          {
            for (int a = 0; a < mesh.SpaceDimension; ++a)
            {
              sum[a] += mesh.Point(ids[k])[a] / corners;
            }
          }
        }
        measure = n > 0 ? static_cast<double>(n) : 1.0;
      }
      for (int a = 0; a < 3; ++a)
      {
        this->Centroids[3 * p + a] = sum[a] / measure;
      }
    }
    return 0;
  }, 1024);
}

void LinearReconstruction::FindSites(const NeighborId* across)
{
  // Copies of a point can only be where faces have no neighbour by ids (two
  // cells that share a point by coordinates but not by id are not matched
  // there): the points of those faces, in the order of their coordinates,
  // equal ones side by side. Each point is its own site, a copy its run's
  // first point's.
  const MeshView& mesh = *this->Mesh;
  const Index points = mesh.NumberOfPoints;
  const int space = mesh.SpaceDimension;
  const int corners = mesh.CornersPerCell();
  this->Site.resize(static_cast<size_t>(points));
  for (Index q = 0; q < points; ++q)
  {
    this->Site[q] = q;
  }
  this->Sites = points;
  this->JoinCopies = false;
  std::vector<Index> open;
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    for (int k = 0; k < corners; ++k)
    {
      if (across[c * corners + k] < 0)
      {
        for (int m = 1; m < corners; ++m)
        {
          open.push_back(mesh.Cell(c)[(k + m) % corners]);
        }
      }
    }
  }
  std::sort(open.begin(), open.end());
  open.erase(std::unique(open.begin(), open.end()), open.end());
  auto same = [&](Index a, Index b) {
    return std::equal(mesh.Point(a), mesh.Point(a) + space, mesh.Point(b));
  };
  std::sort(open.begin(), open.end(), [&](Index a, Index b) {
    return std::lexicographical_compare(
      mesh.Point(a), mesh.Point(a) + space, mesh.Point(b), mesh.Point(b) + space);
  });
  for (size_t i = 1; i < open.size(); ++i)
  {
    if (same(open[i - 1], open[i]))
    {
      this->Site[open[i]] = this->Site[open[i - 1]];
      this->JoinCopies = true;
    }
  }
}

void LinearReconstruction::MatchFacesOnSites(const TaskRunner& runner, std::vector<NeighborId>& across) const
{
  const MeshView& mesh = *this->Mesh;
  const Index entries = mesh.NumberOfCells * mesh.CornersPerCell();
  std::vector<Index> sites(static_cast<size_t>(entries));
  runner.ForRanges(entries, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i)
    {
      sites[i] = this->Site[mesh.Corner(i)];
    }
    return 0;
  });
  MeshView onSites = mesh;
  onSites.Connectivity = sites.data();
  onSites.Connectivity32 = nullptr;
  onSites.Neighbors = nullptr;
  onSites.Around = nullptr;
  across.assign(static_cast<size_t>(entries), -1);
  BuildFaceNeighbors(onSites, across.data(), runner);
}

void LinearReconstruction::GatherAroundSites(const TaskRunner& runner)
{
  // The parents around each site, sorted (a split parent as often as its
  // simplices there).
  const MeshView& mesh = *this->Mesh;
  const Index entries = mesh.NumberOfCells * mesh.CornersPerCell();
  this->AroundStart.assign(static_cast<size_t>(this->Sites) + 1, 0);
  for (Index i = 0; i < entries; ++i)
  {
    ++this->AroundStart[static_cast<size_t>(this->Site[mesh.Corner(i)]) + 1];
  }
  for (Index q = 0; q < this->Sites; ++q)
  {
    this->AroundStart[q + 1] += this->AroundStart[q];
  }
  this->Around.resize(static_cast<size_t>(entries));
  std::vector<Index> next(this->AroundStart.begin(), this->AroundStart.end() - 1);
  for (Index i = 0; i < entries; ++i)
  {
    this->Around[next[this->Site[mesh.Corner(i)]]++] = this->SlotOf[mesh.ParentOf(i / mesh.CornersPerCell())];
  }
  runner.ForRanges(this->Sites, [&](Index begin, Index end) {
    for (Index q = begin; q < end; ++q)
    {
      std::sort(this->Around.begin() + this->AroundStart[q], this->Around.begin() + this->AroundStart[q + 1]);
    }
    return 0;
  });
}

void LinearReconstruction::FindFaceNeighbors(const NeighborId* across, const TaskRunner& runner)
{
  // Per parent, the parents across its simplices' faces (`across`: the
  // simplices' face neighbours on the sites).
  const MeshView& mesh = *this->Mesh;
  const Index parents = mesh.Parents();
  const int corners = mesh.CornersPerCell();
  const int tasks = runner.TasksFor(parents, 1024);
  std::vector<std::vector<Index>> found(static_cast<size_t>(tasks));
  std::vector<Index> count(static_cast<size_t>(parents) + 1, 0);
  runner.RunAll(tasks, [&](int k) {
    for (Index p = RangeBegin(parents, k, tasks); p < RangeBegin(parents, k + 1, tasks); ++p)
    {
      const size_t first = found[k].size();
      for (Index i = this->SimplexStart[p]; i < this->SimplexStart[p + 1]; ++i)
      {
        for (int face = 0; face < corners; ++face)
        {
          const NeighborId n = across[static_cast<size_t>(this->Simplices[i] * corners + face)];
          const Index q = n >= 0 ? this->SlotOf[mesh.ParentOf(n)] : p;
          if (q != p)
          {
            found[k].push_back(q);
          }
        }
      }
      std::sort(found[k].begin() + first, found[k].end());
      found[k].erase(std::unique(found[k].begin() + first, found[k].end()), found[k].end());
      count[p + 1] = static_cast<Index>(found[k].size() - first);
    }
  });
  for (Index p = 0; p < parents; ++p)
  {
    count[p + 1] += count[p];
  }
  this->FaceStart.swap(count);
  this->Faces.clear();
  this->Faces.reserve(static_cast<size_t>(this->FaceStart.back()));
  for (const std::vector<Index>& part : found)
  {
    this->Faces.insert(this->Faces.end(), part.begin(), part.end());
  }
}

void LinearReconstruction::NeighborsOf(Index p, std::vector<Index>& neighbors) const
{
  this->SlotNeighbors(this->SlotOf[p], neighbors);
  for (Index& q : neighbors)
  {
    q = this->ParentOfSlot[q];
  }
  std::sort(neighbors.begin(), neighbors.end());
}

void LinearReconstruction::SlotNeighbors(Index p, std::vector<Index>& neighbors) const
{
  const MeshView& mesh = *this->Mesh;
  neighbors.clear();
  for (Index i = this->SimplexStart[p]; i < this->SimplexStart[p + 1]; ++i)
  {
    const CellCorners ids = mesh.Cell(this->Simplices[i]);
    for (int k = 0; k < mesh.CornersPerCell(); ++k)
    {
      const Index q = this->Site[ids[k]];
      for (Index j = this->AroundStart[q]; j < this->AroundStart[q + 1]; ++j)
      {
        if (this->Around[j] != p)
        {
          neighbors.push_back(this->Around[j]);
        }
      }
    }
  }
  std::sort(neighbors.begin(), neighbors.end());
  neighbors.erase(std::unique(neighbors.begin(), neighbors.end()), neighbors.end());
}

std::size_t LinearReconstruction::MemoryBytes() const
{
  return (this->Centroids.capacity() + this->Frames.capacity()) *
    sizeof(double) +
    (this->SimplexStart.capacity() + this->Simplices.capacity() + this->SlotOf.capacity() +
      this->ParentOfSlot.capacity() + this->AroundStart.capacity() +
      this->Around.capacity() + this->Site.capacity() + this->FaceStart.capacity() + this->Faces.capacity()) *
    sizeof(Index) +
    this->Flat.capacity();
}

void LinearReconstruction::Reconstruct(const double* values, int components, const char* defined,
  Reconstruction mode, const TaskRunner& runner, double* corners) const
{
  const MeshView& mesh = *this->Mesh;
  const Index parents = mesh.Parents();
  // The values (and which exist) in slot order.
  std::vector<double> orderedValues;
  std::vector<char> orderedDefined;
  if (!this->SlotsAreParents)
  {
    orderedValues.resize(static_cast<size_t>(parents) * components);
    orderedDefined.resize(defined ? static_cast<size_t>(parents) : 0);
    runner.ForRanges(parents, [&](Index begin, Index end) {
      for (Index k = begin; k < end; ++k)
      {
        const Index p = this->ParentOfSlot[k];
        std::copy(values + p * components, values + (p + 1) * components, &orderedValues[k * components]);
        if (defined)
        {
          orderedDefined[k] = defined[p];
        }
      }
      return 0;
    });
    values = orderedValues.data();
    defined = defined ? orderedDefined.data() : nullptr;
  }
  const std::vector<double> ranges = mode == Reconstruction::Limited
    ? this->SiteRanges(values, components, defined, runner)
    : std::vector<double>();
  const Input in{ values, components, defined, mode, ranges.data() };
  runner.ForRanges(parents, [&](Index begin, Index end) {
    switch (mesh.CellDimension)
    {
      case 1:
        this->ReconstructRange<1>(begin, end, in, corners);
        break;
      case 2:
        this->ReconstructRange<2>(begin, end, in, corners);
        break;
      default:
        this->ReconstructRange<3>(begin, end, in, corners);
    }
    return 0;
  }, 1024);
}

template <int M>
void LinearReconstruction::Stencil(Index p, const char* defined, int ring, Scratch& scratch) const
{
  using Vector = Eigen::Matrix<double, M, 1>;
  using Matrix = Eigen::Matrix<double, M, M>;
  const int space = this->Mesh->SpaceDimension;
  const double* cp = this->CentroidAt(p);
  const double* frame = this->Frames.empty() ? nullptr : &this->Frames[3 * M * static_cast<size_t>(p)];
  std::vector<Index>& candidates = scratch.Neighbors;
  if (ring == 0)
  {
    candidates.assign(this->Faces.begin() + this->FaceStart[p], this->Faces.begin() + this->FaceStart[p + 1]);
  }
  else
  {
    this->SlotNeighbors(p, candidates);
  }
  if (ring == 2)
  {
    // And the cells around those.
    std::vector<Index> first(candidates);
    std::vector<Index> around;
    for (Index q : first)
    {
      this->SlotNeighbors(q, around);
      candidates.insert(candidates.end(), around.begin(), around.end());
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    candidates.erase(std::remove(candidates.begin(), candidates.end(), p), candidates.end());
  }
  // The neighbours with values; w d, d their offsets in the cell's frame,
  // w = 1 / |c_N - c_P|^2; A = sum w d d^T.
  std::vector<Index>& used = scratch.Used;
  std::vector<double>& weighted = scratch.Weighted;
  used.clear();
  weighted.clear();
  Matrix a = Matrix::Zero();
  for (Index q : candidates)
  {
    if ((defined && !defined[q]) || this->Flat[q])
    {
      continue; // no value, or no measure (its centroid is no place of its value)
    }
    const double* cq = this->CentroidAt(q);
    double d[3] = { 0.0, 0.0, 0.0 };
    for (int i = 0; i < space; ++i)
    {
      d[i] = cq[i] - cp[i];
    }
    const double squared = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (!(squared > 0.0))
    {
      continue; // the same centroid: no direction
    }
    Vector local;
    for (int k = 0; k < M; ++k)
    {
      const double* t = frame ? frame + 3 * k : nullptr;
      local(k) = t ? d[0] * t[0] + d[1] * t[1] + d[2] * t[2] : d[k];
    }
    a += local * local.transpose() / squared;
    used.push_back(q);
    for (int k = 0; k < M; ++k)
    {
      weighted.push_back(local(k) / squared);
    }
  }
  Eigen::Map<Matrix>(scratch.Normal) = a;
}

template <int M>
void LinearReconstruction::FitGradients(Index p, const double* values, int components,
  const char* defined, Scratch& scratch) const
{
  using Vector = Eigen::Matrix<double, M, 1>;
  using Matrix = Eigen::Matrix<double, M, M>;
  const double* u = values + p * components;
  const double* frame = this->Frames.empty() ? nullptr : &this->Frames[3 * M * static_cast<size_t>(p)];
  // The face neighbours, or where they do not span the cell's directions
  // (a corner, a hole, a strip) all the cells around it, or those and the
  // cells around them (a corner cell with one neighbour).
  this->Stencil<M>(p, defined, 0, scratch);
  const bool faces = SpansWell<M>(Eigen::Map<Matrix>(scratch.Normal), 1e-2);
  if (!faces)
  {
    this->Stencil<M>(p, defined, 1, scratch);
  }
  if (!faces && !SpansWell<M>(Eigen::Map<Matrix>(scratch.Normal), 1e-2))
  {
    this->Stencil<M>(p, defined, 2, scratch);
  }
  const Matrix a = Eigen::Map<Matrix>(scratch.Normal);
  const std::vector<Index>& used = scratch.Used;
  const std::vector<double>& weighted = scratch.Weighted;
  const Matrix inverse = faces ? Matrix(a.inverse()) : LeastNormInverse<M>(a);
  // Per component: g = A^+ sum w d (u_N - u_P).
  for (int c = 0; c < components; ++c)
  {
    Vector b = Vector::Zero();
    for (size_t j = 0; j < used.size(); ++j)
    {
      const double uq = values[used[j] * components + c];
      for (int k = 0; k < M; ++k)
      {
        b(k) += weighted[M * j + k] * (uq - u[c]);
      }
    }
    const Vector g = inverse * b;
    double* out = &scratch.Gradient[3 * static_cast<size_t>(c)];
    for (int i = 0; i < 3; ++i)
    {
      double sum = 0.0;
      for (int k = 0; k < M; ++k)
      {
        sum += frame ? g(k) * frame[3 * k + i] : (i == k ? g(k) : 0.0);
      }
      out[i] = sum;
    }
  }
}

void LinearReconstruction::Limit(
  Index p, const double* u, int components, const double* ranges, Scratch& scratch) const
{
  // The bounds: the least and greatest value of the cells around P's
  // corners (P and its neighbours), from the sites' ranges.
  const MeshView& mesh = *this->Mesh;
  const double* cp = this->CentroidAt(p);
  for (int c = 0; c < components; ++c)
  {
    double low = u[c];
    double high = u[c];
    for (Index i = this->SimplexStart[p]; i < this->SimplexStart[p + 1]; ++i)
    {
      const CellCorners ids = mesh.Cell(this->Simplices[i]);
      for (int k = 0; k < mesh.CornersPerCell(); ++k)
      {
        const double* range = ranges + 2 * (this->Site[ids[k]] * components + c);
        low = std::min(low, range[0]);
        high = std::max(high, range[1]);
      }
    }
    double* g = &scratch.Gradient[3 * static_cast<size_t>(c)];
    double phi = 1.0;
    for (Index i = this->SimplexStart[p]; i < this->SimplexStart[p + 1]; ++i)
    {
      const CellCorners ids = mesh.Cell(this->Simplices[i]);
      for (int k = 0; k < mesh.CornersPerCell(); ++k)
      {
        const double* x = mesh.Point(ids[k]);
        double delta = 0.0;
        for (int b = 0; b < mesh.SpaceDimension; ++b)
        {
          delta += g[b] * (x[b] - cp[b]);
        }
        phi = std::min(phi, LimiterFactor(u[c], delta, low, high));
      }
    }
    phi = std::max(0.0, phi);
    for (int b = 0; b < 3; ++b)
    {
      g[b] *= phi;
    }
  }
}

std::vector<double> LinearReconstruction::SiteRanges(
  const double* values, int components, const char* defined, const TaskRunner& runner) const
{
  std::vector<double> ranges(2 * static_cast<size_t>(this->Sites) * components);
  runner.ForRanges(this->Sites, [&](Index begin, Index end) {
    for (Index q = begin; q < end; ++q)
    {
      for (int c = 0; c < components; ++c)
      {
        double low = std::numeric_limits<double>::infinity();
        double high = -low;
        for (Index j = this->AroundStart[q]; j < this->AroundStart[q + 1]; ++j)
        {
          const Index parent = this->Around[j];
          if (!defined || defined[parent])
          {
            low = std::min(low, values[parent * components + c]);
            high = std::max(high, values[parent * components + c]);
          }
        }
        ranges[2 * (q * components + c)] = low;
        ranges[2 * (q * components + c) + 1] = high;
      }
    }
    return 0;
  });
  return ranges;
}

void LinearReconstruction::WriteCorners(
  Index p, const double* u, int components, const Scratch& scratch, double* corners) const
{
  const MeshView& mesh = *this->Mesh;
  const int n = mesh.CornersPerCell();
  const double* cp = this->CentroidAt(p);
  for (Index i = this->SimplexStart[p]; i < this->SimplexStart[p + 1]; ++i)
  {
    const Index s = this->Simplices[i];
    const CellCorners ids = mesh.Cell(s);
    for (int k = 0; k < n; ++k)
    {
      const double* x = mesh.Point(ids[k]);
      double* out = corners + (s * n + k) * components;
      for (int c = 0; c < components; ++c)
      {
        double value = u ? u[c] : 0.0;
        for (int b = 0; b < mesh.SpaceDimension; ++b)
        {
          value += scratch.Gradient[3 * static_cast<size_t>(c) + b] * (x[b] - cp[b]);
        }
        out[c] = value;
      }
    }
  }
}

template <int M>
void LinearReconstruction::ReconstructRange(Index begin, Index end, const Input& in, double* corners) const
{
  Scratch scratch;
  scratch.Gradient.resize(3 * static_cast<size_t>(in.Components));
  for (Index p = begin; p < end; ++p)
  {
    const double* u = in.Values + p * in.Components;
    const bool has = !in.Defined || in.Defined[p];
    std::fill(scratch.Gradient.begin(), scratch.Gradient.end(), 0.0);
    if (has && in.Mode != Reconstruction::Constant)
    {
      this->FitGradients<M>(p, in.Values, in.Components, in.Defined, scratch);
      if (in.Mode == Reconstruction::Limited)
      {
        this->Limit(p, u, in.Components, in.Ranges, scratch);
      }
    }
    this->WriteCorners(p, has ? u : nullptr, in.Components, scratch, corners);
  }
}
} // namespace mp
