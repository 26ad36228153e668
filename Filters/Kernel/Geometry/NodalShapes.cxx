// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/NodalShapes.h"

#include <algorithm>
#include <cmath>

namespace mp
{
namespace
{
// VTK's parametric coordinates of each type's nodes (GetParametricCoords).
// Quad8, Hexa20 and Wedge15 are the first nodes of Quad9, Hexa27 and Wedge18.
const double Edge3Nodes[] = { 0, 0, 0, 1, 0, 0, 0.5, 0, 0 };
const double Triangle6Nodes[] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5, 0, 0, 0.5, 0.5, 0, 0, 0.5, 0 };
const double Quad9Nodes[] = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0, 0, 1, 0.5, 0, 0.5, 1, 0,
  0, 0.5, 0, 0.5, 0.5, 0 };
const double Tetra10Nodes[] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, 0, 0, 0.5, 0.5, 0, 0, 0.5,
  0, 0, 0, 0.5, 0.5, 0, 0.5, 0, 0.5, 0.5 };
const double Hexa27Nodes[] = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1,
  1, 0.5, 0, 0, 1, 0.5, 0, 0.5, 1, 0, 0, 0.5, 0, 0.5, 0, 1, 1, 0.5, 1, 0.5, 1, 1, 0, 0.5, 1, 0, 0,
  0.5, 1, 0, 0.5, 1, 1, 0.5, 0, 1, 0.5, 0, 0.5, 0.5, 1, 0.5, 0.5, 0.5, 0, 0.5, 0.5, 1, 0.5, 0.5,
  0.5, 0, 0.5, 0.5, 1, 0.5, 0.5, 0.5 };
const double Wedge18Nodes[] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 0.5, 0, 0,
  0.5, 0.5, 0, 0, 0.5, 0, 0.5, 0, 1, 0.5, 0.5, 1, 0, 0.5, 1, 0, 0, 0.5, 1, 0, 0.5, 0, 1, 0.5, 0.5,
  0, 0.5, 0.5, 0.5, 0.5, 0, 0.5, 0.5 };
const double Pyramid13Nodes[] = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 0.5, 0, 0, 1, 0.5, 0,
  0.5, 1, 0, 0, 0.5, 0, 0, 0, 0.5, 1, 0, 0.5, 1, 1, 0.5, 0, 1, 0.5 };

/// The mid-edge nodes' corners of the simplices, in VTK's order.
const int SimplexEdges[6][2] = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 3 }, { 2, 3 } };

/// The 1D quadratic Lagrange function of the node at 0 (k = 0), 1 (k = 1)
/// or 1/2 (k = 2) on [0, 1], and its derivative.
inline double Lagrange(int k, double r)
{
  return k == 0 ? (1.0 - r) * (1.0 - 2.0 * r)
                : (k == 1 ? r * (2.0 * r - 1.0) : 4.0 * r * (1.0 - r));
}
inline double LagrangeDerivative(int k, double r)
{
  return k == 0 ? 4.0 * r - 3.0 : (k == 1 ? 4.0 * r - 1.0 : 4.0 - 8.0 * r);
}
/// Which 1D function a node's reference coordinate (0, 1 or 1/2) takes.
inline int LagrangeIndex(double c)
{
  return c == 0.0 ? 0 : (c == 1.0 ? 1 : 2);
}

/// SimplexP2's values alone (the same operations, without the
/// derivatives' tests in every loop: the quadrature's points need only these).
void SimplexP2Values(int d, const double* xi, double* N)
{
  double lambda[4];
  lambda[0] = 1.0;
  for (int a = 0; a < d; ++a)
  {
    lambda[a + 1] = xi[a];
    lambda[0] -= xi[a];
  }
  for (int i = 0; i <= d; ++i)
  {
    N[i] = lambda[i] * (2.0 * lambda[i] - 1.0);
  }
  const int edges = d == 1 ? 1 : (d == 2 ? 3 : 6);
  for (int e = 0; e < edges; ++e)
  {
    N[d + 1 + e] = 4.0 * lambda[SimplexEdges[e][0]] * lambda[SimplexEdges[e][1]];
  }
}

/**
 * Quadratic Lagrange on the d-simplex (Edge3, Triangle6, Tetra10): the
 * corners lambda_i (2 lambda_i - 1), the edges 4 lambda_i lambda_j.
 * N or dN may be null.
 */
void SimplexP2(int d, const double* xi, double* N, double* dN)
{
  if (N && !dN)
  {
    SimplexP2Values(d, xi, N);
    return;
  }
  double lambda[4];
  lambda[0] = 1.0;
  for (int a = 0; a < d; ++a)
  {
    lambda[a + 1] = xi[a];
    lambda[0] -= xi[a];
  }
  // d lambda_i / d xi_a: -1 for i = 0, delta_(i-1)a otherwise.
  auto grad = [](int i, int a) { return i == 0 ? -1.0 : (i - 1 == a ? 1.0 : 0.0); };
  const int edges = d == 1 ? 1 : (d == 2 ? 3 : 6);
  for (int i = 0; i <= d; ++i)
  {
    if (N)
    {
      N[i] = lambda[i] * (2.0 * lambda[i] - 1.0);
    }
    for (int a = 0; dN && a < 3; ++a)
    {
      dN[i * 3 + a] = a < d ? (4.0 * lambda[i] - 1.0) * grad(i, a) : 0.0;
    }
  }
  for (int e = 0; e < edges; ++e)
  {
    const int n = d + 1 + e;
    const int i = SimplexEdges[e][0];
    const int j = SimplexEdges[e][1];
    if (N)
    {
      N[n] = 4.0 * lambda[i] * lambda[j];
    }
    for (int a = 0; dN && a < 3; ++a)
    {
      dN[n * 3 + a] = a < d ? 4.0 * (lambda[j] * grad(i, a) + lambda[i] * grad(j, a)) : 0.0;
    }
  }
}

/// Tensor-product quadratic Lagrange (Quad9, Hexa27) on `nodes`: the
/// three 1D functions of each direction once, then their products.
void TensorQ2(int d, int count, const double* nodes, const double* xi, double* N, double* dN)
{
  double line[3][3];  // line[a][k]: direction a's function k at xi_a
  double slope[3][3]; // and its derivative
  for (int a = 0; a < d; ++a)
  {
    for (int k = 0; k < 3; ++k)
    {
      line[a][k] = Lagrange(k, xi[a]);
      slope[a][k] = LagrangeDerivative(k, xi[a]);
    }
  }
  for (int n = 0; n < count; ++n)
  {
    int k[3] = { 0, 0, 0 };
    for (int a = 0; a < d; ++a)
    {
      k[a] = LagrangeIndex(nodes[n * 3 + a]);
    }
    if (N)
    {
      N[n] = line[0][k[0]] * line[1][k[1]] * (d == 3 ? line[2][k[2]] : 1.0);
    }
    for (int a = 0; dN && a < 3; ++a)
    {
      double product = a < d ? slope[a][k[a]] : 0.0;
      for (int b = 0; b < d; ++b)
      {
        product *= b == a ? 1.0 : line[b][k[b]];
      }
      dN[n * 3 + a] = product;
    }
  }
}

/**
 * Serendipity (Quad8, Hexa20) on the first `count` of `nodes`, in the
 * centred coordinates u = 2 xi - 1 and c = 2 node - 1: a corner
 * 2^-d prod (1 + u_a c_a) (sum u_a c_a - (d - 1)), a mid-edge node (c_m = 0)
 * 2^-(d-1) (1 - u_m^2) prod_(b != m) (1 + u_b c_b).
 */
void Serendipity(int d, int count, const double* nodes, const double* xi, double* N, double* dN)
{
  double u[3];
  for (int a = 0; a < d; ++a)
  {
    u[a] = 2.0 * xi[a] - 1.0;
  }
  for (int n = 0; n < count; ++n)
  {
    double c[3];
    int mid = -1;
    for (int a = 0; a < d; ++a)
    {
      c[a] = 2.0 * nodes[n * 3 + a] - 1.0;
      mid = c[a] == 0.0 ? a : mid;
    }
    // f[a]: the factor of direction a; df[a]: its derivative in u_a.
    double f[3];
    double df[3];
    double extra = 0.0; // a corner's sum u_a c_a - (d - 1)
    for (int a = 0; a < d; ++a)
    {
      f[a] = a == mid ? 1.0 - u[a] * u[a] : 1.0 + u[a] * c[a];
      df[a] = a == mid ? -2.0 * u[a] : c[a];
      extra += u[a] * c[a];
    }
    extra -= d - 1;
    const double scale = mid < 0 ? (d == 2 ? 0.25 : 0.125) : (d == 2 ? 0.5 : 0.25);
    double product = 1.0;
    for (int a = 0; a < d; ++a)
    {
      product *= f[a];
    }
    if (N)
    {
      N[n] = scale * product * (mid < 0 ? extra : 1.0);
    }
    for (int a = 0; dN && a < 3; ++a)
    {
      if (a >= d)
      {
        dN[n * 3 + a] = 0.0;
        continue;
      }
      double others = 1.0;
      for (int b = 0; b < d; ++b)
      {
        others *= b == a ? 1.0 : f[b];
      }
      const double du = mid < 0 ? others * df[a] * extra + product * c[a] : others * df[a];
      dN[n * 3 + a] = 2.0 * scale * du; // d/dxi = 2 d/du
    }
  }
}

/// The wedges' triangle coordinates lambda_0 = 1 - r - s, lambda_1 = r,
/// lambda_2 = s and their gradients in (r, s).
inline void WedgeLambda(const double* xi, double* lambda, double (*grad)[2])
{
  lambda[0] = 1.0 - xi[0] - xi[1];
  lambda[1] = xi[0];
  lambda[2] = xi[1];
  const double g[3][2] = { { -1.0, -1.0 }, { 1.0, 0.0 }, { 0.0, 1.0 } };
  std::copy(&g[0][0], &g[0][0] + 6, &grad[0][0]);
}

/// Writes node n's value and gradient from its derivatives in the
/// triangle coordinates (dl[i] = d/dlambda_i) and in z = 2 xi_2 - 1.
inline void WedgeStore(
  int n, double value, const double* dl, double dz, const double (*grad)[2], double* N, double* dN)
{
  if (N)
  {
    N[n] = value;
  }
  if (dN)
  {
    for (int a = 0; a < 2; ++a)
    {
      dN[n * 3 + a] = dl[0] * grad[0][a] + dl[1] * grad[1][a] + dl[2] * grad[2][a];
    }
    dN[n * 3 + 2] = 2.0 * dz;
  }
}

/**
 * Wedge15 (VTK_QUADRATIC_WEDGE), with z = 2 xi_2 - 1 and z_n = -1 on the
 * bottom, +1 on the top: corner i
 * lambda_i ((1 + z z_n)(2 lambda_i - 1) - (1 - z^2)) / 2, triangle mid-edge
 * node 2 lambda_i lambda_j (1 + z z_n), vertical mid-edge node
 * lambda_i (1 - z^2).
 */
void Wedge15(const double* xi, double* N, double* dN)
{
  double l[3];
  double grad[3][2];
  WedgeLambda(xi, l, grad);
  const double z = 2.0 * xi[2] - 1.0;
  const double bubble = 1.0 - z * z;
  for (int side = 0; side < 2; ++side)
  {
    const double zn = side == 0 ? -1.0 : 1.0;
    const double along = 1.0 + z * zn;
    for (int i = 0; i < 3; ++i)
    {
      double dl[3] = { 0.0, 0.0, 0.0 };
      dl[i] = 0.5 * (along * (4.0 * l[i] - 1.0) - bubble);
      const double value = 0.5 * l[i] * (along * (2.0 * l[i] - 1.0) - bubble);
      const double dz = 0.5 * l[i] * (zn * (2.0 * l[i] - 1.0) + 2.0 * z);
      WedgeStore(side * 3 + i, value, dl, dz, grad, N, dN);
    }
    for (int e = 0; e < 3; ++e)
    {
      const int i = SimplexEdges[e][0];
      const int j = SimplexEdges[e][1];
      double dl[3] = { 0.0, 0.0, 0.0 };
      dl[i] = 2.0 * l[j] * along;
      dl[j] = 2.0 * l[i] * along;
      WedgeStore(
        6 + side * 3 + e, 2.0 * l[i] * l[j] * along, dl, 2.0 * l[i] * l[j] * zn, grad, N, dN);
    }
  }
  for (int i = 0; i < 3; ++i)
  {
    double dl[3] = { 0.0, 0.0, 0.0 };
    dl[i] = bubble;
    WedgeStore(12 + i, l[i] * bubble, dl, -2.0 * l[i] * z, grad, N, dN);
  }
}

/**
 * Wedge18 (VTK_BIQUADRATIC_QUADRATIC_WEDGE): the quadratic triangle's
 * function of the node's (xi_0, xi_1) times the quadratic line's of its
 * xi_2.
 */
void Wedge18(const double* xi, double* N, double* dN)
{
  // Each node's Triangle6 node and 1D Lagrange function (LagrangeIndex).
  static const int triangleNode[18] = { 0, 1, 2, 0, 1, 2, 3, 4, 5, 3, 4, 5, 0, 1, 2, 3, 4, 5 };
  static const int lineNode[18] = { 0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2, 2, 2 };
  double triangle[6];
  double triangleSlope[18];
  SimplexP2(2, xi, triangle, triangleSlope);
  for (int n = 0; n < 18; ++n)
  {
    const int k = triangleNode[n];
    const double line = Lagrange(lineNode[n], xi[2]);
    if (N)
    {
      N[n] = triangle[k] * line;
    }
    if (dN)
    {
      dN[n * 3 + 0] = triangleSlope[k * 3 + 0] * line;
      dN[n * 3 + 1] = triangleSlope[k * 3 + 1] * line;
      dN[n * 3 + 2] = triangle[k] * LagrangeDerivative(lineNode[n], xi[2]);
    }
  }
}

/**
 * Pyramid13 (VTK_QUADRATIC_PYRAMID): VTK's functions on the cube
 * [0, 1]^3 collapsed at t = xi_2 = 1. With u = 2 xi_0 - 1, v = 2 xi_1 - 1,
 * a base corner's signs (s_u, s_v) and a = s_u u, b = s_v v, B its
 * bilinear function (1 + a)(1 + b) / 4:
 *  - base corner: B (1 - t) ((a + b - 1)(1 + t) - t (1 + 2 a b));
 *  - apex: t (2 t - 1);
 *  - base mid-edge node along direction p, across direction q (sign s_q,
 *    b = s_q times q's centred coordinate):
 *    4 xi_p (1 - xi_p) (1 + b) / 2 (1 - t)(1 - b t);
 *  - mid-edge node between base corner c and the apex: 4 t (1 - t) B_c.
 */
void Pyramid13(const double* xi, double* N, double* dN)
{
  const double t = xi[2];
  for (int n = 0; n < 13; ++n)
  {
    const double* node = Pyramid13Nodes + 3 * n;
    double value = 0.0;
    double d[3] = { 0.0, 0.0, 0.0 };
    if (node[2] == 1.0)
    {
      value = t * (2.0 * t - 1.0);
      d[2] = 4.0 * t - 1.0;
    }
    else if (node[0] == 0.5 || node[1] == 0.5)
    {
      const int p = node[0] == 0.5 ? 0 : 1;
      const int q = 1 - p;
      const double sq = 2.0 * node[q] - 1.0;
      const double b = sq * (2.0 * xi[q] - 1.0);
      const double bubble = 4.0 * xi[p] * (1.0 - xi[p]);
      const double across = 0.5 * (1.0 + b) * (1.0 - t) * (1.0 - b * t);
      value = bubble * across;
      d[p] = 4.0 * (1.0 - 2.0 * xi[p]) * across;
      d[q] = bubble * (1.0 - t) * sq * ((1.0 - b * t) - t * (1.0 + b));
      d[2] = bubble * 0.5 * (1.0 + b) * (-(1.0 - b * t) - b * (1.0 - t));
    }
    else
    {
      const double su = 2.0 * node[0] - 1.0;
      const double sv = 2.0 * node[1] - 1.0;
      const double a = su * (2.0 * xi[0] - 1.0);
      const double b = sv * (2.0 * xi[1] - 1.0);
      const double B = 0.25 * (1.0 + a) * (1.0 + b);
      const double dB[2] = { 0.5 * su * (1.0 + b), 0.5 * sv * (1.0 + a) };
      if (node[2] == 0.5)
      {
        value = 4.0 * t * (1.0 - t) * B;
        d[0] = 4.0 * t * (1.0 - t) * dB[0];
        d[1] = 4.0 * t * (1.0 - t) * dB[1];
        d[2] = (4.0 - 8.0 * t) * B;
      }
      else
      {
        const double G = (a + b - 1.0) * (1.0 + t) - t * (1.0 + 2.0 * a * b);
        const double dG[2] = { 2.0 * su * ((1.0 + t) - 2.0 * t * b),
          2.0 * sv * ((1.0 + t) - 2.0 * t * a) };
        value = B * (1.0 - t) * G;
        d[0] = (1.0 - t) * (dB[0] * G + B * dG[0]);
        d[1] = (1.0 - t) * (dB[1] * G + B * dG[1]);
        d[2] = B * (-G + (1.0 - t) * (a + b - 2.0 - 2.0 * a * b));
      }
    }
    if (N)
    {
      N[n] = value;
    }
    if (dN)
    {
      std::copy(d, d + 3, dN + 3 * n);
    }
  }
}

/// The shape functions (N) and derivatives (dN) of any type; either may
/// be null.
void Evaluate(NodalType type, const double* xi, double* N, double* dN)
{
  switch (type)
  {
    case NodalType::Edge3:
      SimplexP2(1, xi, N, dN);
      break;
    case NodalType::Triangle6:
      SimplexP2(2, xi, N, dN);
      break;
    case NodalType::Tetra10:
      SimplexP2(3, xi, N, dN);
      break;
    case NodalType::Quad8:
      Serendipity(2, 8, Quad9Nodes, xi, N, dN);
      break;
    case NodalType::Quad9:
      TensorQ2(2, 9, Quad9Nodes, xi, N, dN);
      break;
    case NodalType::Hexa20:
      Serendipity(3, 20, Hexa27Nodes, xi, N, dN);
      break;
    case NodalType::Hexa27:
      TensorQ2(3, 27, Hexa27Nodes, xi, N, dN);
      break;
    case NodalType::Wedge15:
      Wedge15(xi, N, dN);
      break;
    case NodalType::Wedge18:
      Wedge18(xi, N, dN);
      break;
    case NodalType::Pyramid13:
      Pyramid13(xi, N, dN);
      break;
    case NodalType::None:
      break;
  }
}

/// The linear simplex's functions (barycentric coordinates) on d
/// dimensions; N or dN may be null.
void LinearSimplex(int d, const double* xi, double* N, double* dN)
{
  for (int i = 0; i <= d; ++i)
  {
    if (N)
    {
      N[i] = i == 0 ? 1.0 : xi[i - 1];
      for (int a = 0; i == 0 && a < d; ++a)
      {
        N[0] -= xi[a];
      }
    }
    for (int a = 0; dN && a < 3; ++a)
    {
      dN[i * 3 + a] = a >= d ? 0.0 : (i == 0 ? -1.0 : (a == i - 1 ? 1.0 : 0.0));
    }
  }
}

/// The linear wedge's functions: lambda_i times 1 - t (bottom) or t (top).
void LinearWedge(const double* xi, double* N, double* dN)
{
  double l[3];
  double grad[3][2];
  WedgeLambda(xi, l, grad);
  for (int n = 0; n < 6; ++n)
  {
    const int i = n % 3;
    const double line = n < 3 ? 1.0 - xi[2] : xi[2];
    if (N)
    {
      N[n] = l[i] * line;
    }
    if (dN)
    {
      dN[n * 3 + 0] = grad[i][0] * line;
      dN[n * 3 + 1] = grad[i][1] * line;
      dN[n * 3 + 2] = n < 3 ? -l[i] : l[i];
    }
  }
}

/**
 * The multilinear functions of the first `corners` of `nodes` (whose
 * coordinates are 0 or 1) in `span` directions: prod xi_a or 1 - xi_a. The
 * pyramid's apex (`apex`, or -1) takes t = xi_2 alone, so that its base
 * corners' factor 1 - t collapses the cube.
 */
void Multilinear(
  int span, int corners, int apex, const double* nodes, const double* xi, double* N, double* dN)
{
  for (int n = 0; n < corners; ++n)
  {
    double f[3];
    double df[3];
    for (int a = 0; a < span; ++a)
    {
      const bool one = nodes[n * 3 + a] == 1.0;
      const bool skip = n == apex && a < 2;
      f[a] = skip ? 1.0 : (one ? xi[a] : 1.0 - xi[a]);
      df[a] = skip ? 0.0 : (one ? 1.0 : -1.0);
    }
    if (N)
    {
      N[n] = span == 2 ? f[0] * f[1] : f[0] * f[1] * f[2];
    }
    for (int a = 0; dN && a < 3; ++a)
    {
      double product = a < span ? df[a] : 0.0;
      for (int b = 0; b < span; ++b)
      {
        product *= b == a ? 1.0 : f[b];
      }
      dN[n * 3 + a] = product;
    }
  }
}
} // namespace

int NodalNodeCount(NodalType type)
{
  static const int counts[] = { 0, 3, 6, 8, 9, 10, 20, 27, 15, 18, 13 };
  return counts[static_cast<int>(type)];
}

int NodalCornerCount(NodalType type)
{
  static const int counts[] = { 0, 2, 3, 4, 4, 4, 8, 8, 6, 6, 5 };
  return counts[static_cast<int>(type)];
}

int NodalCellDimension(NodalType type)
{
  static const int dimensions[] = { 0, 1, 2, 2, 2, 3, 3, 3, 3, 3, 3 };
  return dimensions[static_cast<int>(type)];
}

int NodalDegree(NodalType type)
{
  static const int degrees[] = { 0, 2, 2, 3, 4, 2, 4, 6, 3, 4, 6 };
  return degrees[static_cast<int>(type)];
}

void NodalReferenceNodes(NodalType type, double* xi)
{
  const double* table = nullptr;
  switch (type)
  {
    case NodalType::Edge3:
      table = Edge3Nodes;
      break;
    case NodalType::Triangle6:
      table = Triangle6Nodes;
      break;
    case NodalType::Quad8:
    case NodalType::Quad9:
      table = Quad9Nodes;
      break;
    case NodalType::Tetra10:
      table = Tetra10Nodes;
      break;
    case NodalType::Hexa20:
    case NodalType::Hexa27:
      table = Hexa27Nodes;
      break;
    case NodalType::Wedge15:
    case NodalType::Wedge18:
      table = Wedge18Nodes;
      break;
    case NodalType::Pyramid13:
      table = Pyramid13Nodes;
      break;
    case NodalType::None:
      return;
  }
  std::copy(table, table + 3 * NodalNodeCount(type), xi);
}

void NodalValues(NodalType type, const double* xi, double* N)
{
  Evaluate(type, xi, N, nullptr);
}

void NodalDerivatives(NodalType type, const double* xi, double* dN)
{
  Evaluate(type, xi, nullptr, dN);
}

void NodalValuesAndDerivatives(NodalType type, const double* xi, double* N, double* dN)
{
  Evaluate(type, xi, N, dN);
}

void NodalCornerFunctions(NodalType type, const double* xi, double* N, double* dN)
{
  switch (type)
  {
    case NodalType::Edge3:
    case NodalType::Triangle6:
    case NodalType::Tetra10:
      LinearSimplex(NodalCellDimension(type), xi, N, dN);
      break;
    case NodalType::Wedge15:
    case NodalType::Wedge18:
      LinearWedge(xi, N, dN);
      break;
    case NodalType::Quad8:
    case NodalType::Quad9:
      Multilinear(2, 4, -1, Quad9Nodes, xi, N, dN);
      break;
    case NodalType::Hexa20:
    case NodalType::Hexa27:
      Multilinear(3, 8, -1, Hexa27Nodes, xi, N, dN);
      break;
    case NodalType::Pyramid13:
      Multilinear(3, 5, 4, Pyramid13Nodes, xi, N, dN);
      break;
    case NodalType::None:
      break;
  }
}

} // namespace mp
