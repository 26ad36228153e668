// SPDX-License-Identifier: BSD-3-Clause
// LinearReconstruction's fields (LinearReconstruction.h): per parent, the
// gradient's least-squares fit over its neighbours, the limiter and the
// values at its corners. The geometry they read: LinearReconstruction.cxx.
#include "Transfer/LinearReconstruction.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mp
{
namespace
{
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
        std::copy(
          values + p * components, values + (p + 1) * components, &orderedValues[k * components]);
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
  runner.ForRanges(
    parents,
    [&](Index begin, Index end) {
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
    },
    1024);
}

template <int M>
void LinearReconstruction::Stencil(Index p, const char* defined, int ring, Scratch& scratch) const
{
  using Vector = Eigen::Matrix<double, M, 1>;
  using Matrix = Eigen::Matrix<double, M, M>;
  const int space = this->Mesh->SpaceDimension;
  const double* cp = this->CentroidAt(p);
  const double* frame =
    this->Frames.empty() ? nullptr : &this->Frames[3 * M * static_cast<size_t>(p)];
  std::vector<Index>& candidates = scratch.Neighbors;
  if (ring == 0)
  {
    candidates.assign(
      this->Faces.begin() + this->FaceStart[p], this->Faces.begin() + this->FaceStart[p + 1]);
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
void LinearReconstruction::FitGradients(
  Index p, const double* values, int components, const char* defined, Scratch& scratch) const
{
  using Vector = Eigen::Matrix<double, M, 1>;
  using Matrix = Eigen::Matrix<double, M, M>;
  const double* u = values + p * components;
  const double* frame =
    this->Frames.empty() ? nullptr : &this->Frames[3 * M * static_cast<size_t>(p)];
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
void LinearReconstruction::ReconstructRange(
  Index begin, Index end, const Input& in, double* corners) const
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
