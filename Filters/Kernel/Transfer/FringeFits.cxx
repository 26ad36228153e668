// SPDX-License-Identifier: BSD-3-Clause
// The weights of a fringe stencil (FringeFits.h): the weighted least-squares
// fit in the stencil's frame, and its curved stencils' normal coordinates.
#include "Transfer/FringeFits.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <utility>

namespace mp
{
namespace
{
using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 10, 10>;
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 10, 1>;

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
 * The weighted mean square of a stencil's normal coordinates (in units of
 * h^2, beyond what the columns before them fit) above which the fit takes
 * them as a column: on a surface of radius R they are of the order of
 * (h / 2R)^2; points written in single precision leave some 1e-12 on a
 * plane, rounding some 1e-30; a second normal coordinate of a plane curve
 * nearly a multiple of the first leaves its rounding.
 */
constexpr double CurvedNormalSpread = 1e-10;

/**
 * The largest value at i (in units of h) of a normal coordinate that the
 * tangent fit gives and that counts as reproducing it (0 at i): rounding
 * leaves some 1e-16 on a plane or a straight line.
 */
constexpr double FlatMiss = 1e-12;

/**
 * A quadratic column of a curved stencil's fit that its columns before it
 * (1, the tangent coordinates, the normal ones) fit to all but this part
 * of its mean square is left out: on a sphere the normal coordinate is
 * nearly (u^2 + v^2) / 2R, and fitting both would fit the rest of the
 * sphere's shape (its fourth-order terms) with large weights.
 */
constexpr double DependentQuadratic = 1e-3;

/**
 * The columns of a curved stencil's fit, in the order they are tried: the
 * constant and tangent coordinates, the normal coordinates whose spread
 * beyond them is above CurvedNormalSpread, the quadratic monomials not
 * nearly fitted by those (DependentQuadratic). `G` is the weighted normal
 * matrix of the tangent monomials (first `linear` of them linear) then
 * the `normals` normal coordinates. Empty when no normal coordinate is kept
 * (the points' normal coordinates affine in their tangent ones, or too few
 * points to tell).
 */
std::vector<int> CurvedColumns(const Small& G, int linear, int terms, int normals)
{
  std::vector<int> kept;
  bool curved = false;
  auto residual = [&](int j) {
    Small K(kept.size(), kept.size());
    SmallVector g(kept.size());
    for (size_t a = 0; a < kept.size(); ++a)
    {
      g(a) = G(kept[a], j);
      for (size_t b = 0; b < kept.size(); ++b)
      {
        K(a, b) = G(kept[a], kept[b]);
      }
    }
    return G(j, j) - g.dot(K.ldlt().solve(g));
  };
  for (int j = 0; j < linear; ++j)
  {
    kept.push_back(j);
  }
  for (int j = terms; j < terms + normals; ++j)
  {
    if (residual(j) > CurvedNormalSpread)
    {
      kept.push_back(j);
      curved = true;
    }
  }
  for (int j = linear; j < terms && curved; ++j)
  {
    if (residual(j) > DependentQuadratic * G(j, j))
    {
      kept.push_back(j);
    }
  }
  return curved ? kept : std::vector<int>();
}

/// The points of one fit: their coordinates in i's frame, scaled by h, and their weights omega.
struct FitPoints
{
  const MeshView& Mesh;
  const StencilFrame& Frame;
  const double* Xi;
  const std::vector<Index>& Points;
  int Degree;
  double H = 0.0;
  const FitCoverage* Coverage = nullptr;

  /**
   * The monomials of (x_r - x_i) / h in i's frame at point r (coordinates
   * of order 1 about i) and its weight omega, larger near i (the fit is
   * evaluated at i: near points tell most about it) and, with Coverage,
   * smaller on points less covered (FitCoverage); `spread`, when given,
   * the weight without Coverage's factor (the geometry's alone).
   */
  void MonomialsAt(Index r, double& omega, SmallVector& v, double* spread = nullptr) const
  {
    const int d = this->Frame.Dimension;
    double y[3];
    double distance2 = 0.0;
    this->Frame.Offset(
      this->Mesh, this->Mesh.Point(this->Points[static_cast<size_t>(r)]), this->Xi, y);
    for (int a = 0; a < d; ++a)
    {
      y[a] /= this->H;
      distance2 += y[a] * y[a];
    }
    omega = 1.0 / ((distance2 + 0.25) * (distance2 + 0.25));
    if (spread)
    {
      *spread = omega;
    }
    if (this->Coverage)
    {
      const Index k = this->Points[static_cast<size_t>(r)];
      omega *= std::pow(std::min(1.0, this->Coverage->Fraction[k]), this->Coverage->Power);
    }
    Monomials(y, d, this->Degree, v.data());
  }

  /// u: the `terms` monomials at r, then its normal coordinates over h.
  void ColumnsAt(Index r, int terms, double& omega, SmallVector& v, SmallVector& u) const
  {
    this->MonomialsAt(r, omega, v);
    double z[3];
    this->Frame.NormalOffset(
      this->Mesh, this->Mesh.Point(this->Points[static_cast<size_t>(r)]), this->Xi, z);
    u.head(terms) = v;
    for (int b = 0; b < this->Frame.Normals; ++b)
    {
      u(terms + b) = z[b] / this->H;
    }
  }
};

/**
 * A curved stencil's weights (on a surface or a curve): the fit also
 * through the points' normal coordinates, so that it reproduces the
 * ambient affine functions (a linear Source field on a trace, on a sphere
 * in a volume); `tangent` (the tangent fit's weights, stable) where those
 * reproduce the normal coordinates already (a flat stencil), where the
 * points do not determine the fit through them (too few, or their normal
 * coordinates affine in the tangent ones while i is off that line) or
 * where those weights amplify more than QuadraticAmplification (`ambient`
 * false then: only the tangent coordinates' affine functions).
 */
std::vector<double> CurvedWeights(const FitPoints& fit, Index m, int terms, double omegaSum,
  std::vector<double> tangent, bool& ambient)
{
  const int all = terms + fit.Frame.Normals;
  SmallVector v(terms);
  SmallVector u(all);
  Small X = Small::Zero(all, all);
  SmallVector miss = SmallVector::Zero(all); // the tangent fit's values of the columns at i
  for (Index r = 0; r < m; ++r)
  {
    double omega;
    fit.ColumnsAt(r, terms, omega, v, u);
    X += (omega / omegaSum) * u * u.transpose();
    miss += tangent[static_cast<size_t>(r)] * u;
  }
  ambient = miss.tail(fit.Frame.Normals).cwiseAbs().maxCoeff() <= FlatMiss;
  const std::vector<int> kept = ambient
    ? std::vector<int>()
    : CurvedColumns(X, fit.Frame.Dimension + 1, terms, fit.Frame.Normals);
  if (kept.empty())
  {
    return tangent;
  }
  const int k = static_cast<int>(kept.size());
  Small K(k, k);
  for (int a = 0; a < k; ++a)
  {
    for (int b = 0; b < k; ++b)
    {
      K(a, b) = X(kept[a], kept[b]);
    }
  }
  SmallVector e = SmallVector::Zero(k);
  e(0) = 1.0; // the fit's value at i; the constant is kept[0]
  const SmallVector c = K.ldlt().solve(e);
  std::vector<double> w(static_cast<size_t>(m));
  double amplification = 0.0;
  for (Index r = 0; r < m; ++r)
  {
    double omega;
    fit.ColumnsAt(r, terms, omega, v, u);
    double value = 0.0;
    for (int a = 0; a < k; ++a)
    {
      value += u(kept[a]) * c(a);
    }
    w[static_cast<size_t>(r)] = omega * value / omegaSum;
    amplification += std::abs(w[static_cast<size_t>(r)]);
  }
  ambient = amplification <= QuadraticAmplification;
  return ambient ? w : tangent;
}
} // namespace

std::vector<double> FitWeights(const MeshView& mesh, const StencilFrame& frame, Index i,
  const std::vector<Index>& points, size_t keep, int degree, bool* ambient,
  const FitCoverage* coverage)
{
  bool reproduces = true;
  if (ambient)
  {
    *ambient = true;
  }
  const int d = frame.Dimension;
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
    double y[3];
    frame.Offset(mesh, mesh.Point(points[r]), xi, y);
    for (int a = 0; a < d; ++a)
    {
      h = std::max(h, std::abs(y[a]));
    }
  }
  if (!(h > 0.0))
  {
    return {};
  }
  // The normal matrix G = sum_k omega_k v_k v_k^T (v_k the monomials at
  // k, FitPoints) summed row by row, at most 10 x 10 on the stack; the
  // monomials made again for the weights rather than kept (no matrix of
  // points x terms to allocate per fit).
  const FitPoints fit{ mesh, frame, xi, points, degree, h, coverage };
  Small G = Small::Zero(terms, terms);
  // (With coverage, the same normal matrix without its factors, whose
  // spectrum says whether the points determine the fit: how well their
  // values are known does not.)
  Small spreadG = Small::Zero(coverage ? terms : 0, coverage ? terms : 0);
  SmallVector v(terms);
  double omegaSum = 0.0;
  double spreadSum = 0.0;
  for (Index r = 0; r < m; ++r)
  {
    double omega;
    double spread;
    fit.MonomialsAt(r, omega, v, &spread);
    G.selfadjointView<Eigen::Lower>().rankUpdate(v, omega);
    omegaSum += omega;
    if (coverage)
    {
      spreadG.selfadjointView<Eigen::Lower>().rankUpdate(v, spread);
      spreadSum += spread;
    }
  }
  G = G.selfadjointView<Eigen::Lower>();
  G /= omegaSum;
  if (coverage)
  {
    spreadG = spreadG.selfadjointView<Eigen::Lower>();
    spreadG /= spreadSum;
  }
  SmallVector e = SmallVector::Zero(terms);
  e(0) = 1.0; // the fit's value at i (the origin of the coordinates)
  // The weighted fit's value at i: w_k = omega_k v_k . G^-1 e / sum omega.
  const SmallVector c = G.ldlt().solve(e);
  std::vector<double> w(static_cast<size_t>(m));
  double amplification = 0.0;
  for (Index r = 0; r < m; ++r)
  {
    double omega;
    fit.MonomialsAt(r, omega, v);
    w[static_cast<size_t>(r)] = omega * v.dot(c) / omegaSum;
    amplification += std::abs(w[static_cast<size_t>(r)]);
  }
  // (Not "> bound": a singular G gives NaN weights, rejected too.) Most
  // one-sided quadratic fits stop here, before the spectrum's cost.
  if (degree == 2 && !(amplification <= QuadraticAmplificationIn(mesh, frame)))
  {
    return {};
  }
  // Points nearly on a line or a plane (or a conic) do not determine the
  // fit, whatever its weights (on a Gmsh wedge pair, quadratic fits
  // accepted on their amplification alone gave 17 times the interior's
  // error).
  if (Eigen::SelfAdjointEigenSolver<Small>(coverage ? spreadG : G, Eigen::EigenvaluesOnly)
        .eigenvalues()
        .minCoeff() < (degree == 1 ? 1e-2 : 1e-4))
  {
    return {};
  }
  // Weighed by how well their values are known, the points must determine
  // a quadratic fit too: where only a few points covered in part pin one
  // of its directions (a layer of a hexahedral Input beyond the source's
  // face, its second derivative across the face given by two points at the
  // Input's edges), the fit carries their errors many times over.
  if (coverage && degree == 2 &&
    Eigen::SelfAdjointEigenSolver<Small>(G, Eigen::EigenvaluesOnly).eigenvalues().minCoeff() <
      WeighedQuadraticSpread)
  {
    return {};
  }
  if (frame.Normals == 0)
  {
    return w;
  }
  w = CurvedWeights(fit, m, terms, omegaSum, std::move(w), reproduces);
  if (ambient)
  {
    *ambient = reproduces;
  }
  return w;
}
} // namespace mp
