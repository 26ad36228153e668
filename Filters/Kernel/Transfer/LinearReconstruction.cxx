// SPDX-License-Identifier: BSD-3-Clause
#include "Transfer/LinearReconstruction.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

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
 * The least-squares normal matrix A's (least-norm) inverse: A^-1 by
 * Cholesky when the neighbours span all M directions well, else the
 * pseudo-inverse without the directions they leave (nearly) open.
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
  Eigen::LLT<Matrix> llt(a);
  if (llt.info() == Eigen::Success)
  {
    const auto d = llt.matrixLLT().diagonal();
    const double smallest = d.minCoeff();
    if (smallest * smallest > 1e-10 * scale)
    {
      return llt.solve(Matrix::Identity());
    }
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
  this->FindSites();
  this->GatherAroundSites(runner);
}

void LinearReconstruction::GroupSimplices()
{
  // A counting sort of the simplices by parent.
  const MeshView& mesh = *this->Mesh;
  const Index parents = mesh.Parents();
  const Index cells = mesh.NumberOfCells;
  this->SimplexStart.assign(static_cast<size_t>(parents) + 1, 0);
  for (Index c = 0; c < cells; ++c)
  {
    ++this->SimplexStart[static_cast<size_t>(mesh.ParentOf(c)) + 1];
  }
  for (Index p = 0; p < parents; ++p)
  {
    this->SimplexStart[p + 1] += this->SimplexStart[p];
  }
  this->Simplices.resize(static_cast<size_t>(cells));
  std::vector<Index> next(this->SimplexStart.begin(), this->SimplexStart.end() - 1);
  for (Index c = 0; c < cells; ++c)
  {
    this->Simplices[next[mesh.ParentOf(c)]++] = c;
  }
}

void LinearReconstruction::MeasureParents(const TaskRunner& runner)
{
  const MeshView& mesh = *this->Mesh;
  const Index parents = mesh.Parents();
  const int corners = mesh.CornersPerCell();
  const bool framed = !mesh.IsVolumeMesh();
  this->Centroids.assign(3 * static_cast<size_t>(parents), 0.0);
  this->Measures.assign(static_cast<size_t>(parents), 0.0);
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
      this->Measures[p] = measure;
      for (int a = 0; a < 3; ++a)
      {
        this->Centroids[3 * p + a] = measure > 0.0 ? sum[a] / measure : 0.0;
      }
    }
    return 0;
  }, 1024);
}

void LinearReconstruction::FindSites()
{
  // Points in the order of their coordinates: equal ones side by side.
  const MeshView& mesh = *this->Mesh;
  const Index points = mesh.NumberOfPoints;
  const int space = mesh.SpaceDimension;
  std::vector<Index> order(static_cast<size_t>(points));
  for (Index q = 0; q < points; ++q)
  {
    order[q] = q;
  }
  auto same = [&](Index a, Index b) {
    return std::equal(mesh.Point(a), mesh.Point(a) + space, mesh.Point(b));
  };
  std::sort(order.begin(), order.end(), [&](Index a, Index b) {
    return std::lexicographical_compare(
      mesh.Point(a), mesh.Point(a) + space, mesh.Point(b), mesh.Point(b) + space);
  });
  this->Site.resize(static_cast<size_t>(points));
  this->Sites = 0;
  for (Index i = 0; i < points; ++i)
  {
    if (i > 0 && !same(order[i - 1], order[i]))
    {
      ++this->Sites;
    }
    this->Site[order[i]] = this->Sites;
  }
  this->Sites += points > 0 ? 1 : 0;
}

void LinearReconstruction::GatherAroundSites(const TaskRunner& runner)
{
  // The parents around each site, each once.
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
    this->Around[next[this->Site[mesh.Corner(i)]]++] = mesh.ParentOf(i / mesh.CornersPerCell());
  }
  runner.ForRanges(this->Sites, [&](Index begin, Index end) {
    for (Index q = begin; q < end; ++q)
    {
      std::sort(this->Around.begin() + this->AroundStart[q], this->Around.begin() + this->AroundStart[q + 1]);
    }
    return 0;
  });
}

void LinearReconstruction::NeighborsOf(Index p, std::vector<Index>& neighbors) const
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
  return (this->Centroids.capacity() + this->Measures.capacity() + this->Frames.capacity()) *
    sizeof(double) +
    (this->SimplexStart.capacity() + this->Simplices.capacity() + this->AroundStart.capacity() +
      this->Around.capacity() + this->Site.capacity()) *
    sizeof(Index);
}

void LinearReconstruction::Reconstruct(const double* values, int components, const char* defined,
  Reconstruction mode, const TaskRunner& runner, double* corners) const
{
  const MeshView& mesh = *this->Mesh;
  const Index parents = mesh.Parents();
  runner.ForRanges(parents, [&](Index begin, Index end) {
    switch (mesh.CellDimension)
    {
      case 1:
        this->ReconstructRange<1>(begin, end, values, components, defined, mode, corners);
        break;
      case 2:
        this->ReconstructRange<2>(begin, end, values, components, defined, mode, corners);
        break;
      default:
        this->ReconstructRange<3>(begin, end, values, components, defined, mode, corners);
    }
    return 0;
  }, 1024);
}

template <int M>
void LinearReconstruction::FitGradients(Index p, const double* values, int components,
  const char* defined, Scratch& scratch) const
{
  using Vector = Eigen::Matrix<double, M, 1>;
  using Matrix = Eigen::Matrix<double, M, M>;
  const int space = this->Mesh->SpaceDimension;
  const double* u = values + p * components;
  const double* cp = this->Centroid(p);
  const double* frame = this->Frames.empty() ? nullptr : &this->Frames[3 * M * static_cast<size_t>(p)];
  // The neighbours with values; w d, d their offsets in the cell's frame,
  // w = 1 / |c_N - c_P|^2; A = sum w d d^T.
  this->NeighborsOf(p, scratch.Neighbors);
  std::vector<Index>& used = scratch.Used;
  std::vector<double>& weighted = scratch.Weighted;
  used.clear();
  weighted.clear();
  Matrix a = Matrix::Zero();
  for (Index q : scratch.Neighbors)
  {
    if (defined && !defined[q])
    {
      continue;
    }
    const double* cq = this->Centroid(q);
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
  const Matrix inverse = LeastNormInverse<M>(a);
  // Per component: g = A^+ sum w d (u_N - u_P), and the range of u_P and its neighbours.
  for (int c = 0; c < components; ++c)
  {
    Vector b = Vector::Zero();
    double low = u[c];
    double high = u[c];
    for (size_t j = 0; j < used.size(); ++j)
    {
      const double uq = values[used[j] * components + c];
      for (int k = 0; k < M; ++k)
      {
        b(k) += weighted[M * j + k] * (uq - u[c]);
      }
      low = std::min(low, uq);
      high = std::max(high, uq);
    }
    scratch.Low[c] = low;
    scratch.High[c] = high;
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

void LinearReconstruction::Limit(Index p, const double* u, int components, Scratch& scratch) const
{
  const MeshView& mesh = *this->Mesh;
  const double* cp = this->Centroid(p);
  for (int c = 0; c < components; ++c)
  {
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
        phi = std::min(phi, LimiterFactor(u[c], delta, scratch.Low[c], scratch.High[c]));
      }
    }
    phi = std::max(0.0, phi);
    for (int b = 0; b < 3; ++b)
    {
      g[b] *= phi;
    }
  }
}

void LinearReconstruction::WriteCorners(
  Index p, const double* u, int components, const Scratch& scratch, double* corners) const
{
  const MeshView& mesh = *this->Mesh;
  const int n = mesh.CornersPerCell();
  const double* cp = this->Centroid(p);
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
void LinearReconstruction::ReconstructRange(Index begin, Index end, const double* values,
  int components, const char* defined, Reconstruction mode, double* corners) const
{
  Scratch scratch;
  scratch.Gradient.resize(3 * static_cast<size_t>(components));
  scratch.Low.resize(static_cast<size_t>(components));
  scratch.High.resize(static_cast<size_t>(components));
  for (Index p = begin; p < end; ++p)
  {
    const double* u = values + p * components;
    const bool has = !defined || defined[p];
    std::fill(scratch.Gradient.begin(), scratch.Gradient.end(), 0.0);
    if (has && mode != Reconstruction::Constant)
    {
      this->FitGradients<M>(p, values, components, defined, scratch);
      if (mode == Reconstruction::Limited)
      {
        this->Limit(p, u, components, scratch);
      }
    }
    this->WriteCorners(p, has ? u : nullptr, components, scratch, corners);
  }
}
} // namespace mp
