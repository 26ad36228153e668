// SPDX-License-Identifier: BSD-3-Clause
// Test cells for the second-order shape functions (Geometry/NodalShapes.h),
// shared by TestNodalShapes and TestNodalReference: VTK's reference nodes,
// random reference points, the corners' (multi)linear functions written
// again independently of the kernel, straight cells on mapped corners, and
// the isoparametric map.
#ifndef MeshProjection_NodalTestCells_h
#define MeshProjection_NodalTestCells_h

#include "Geometry/NodalShapes.h"

#include <random>
#include <vector>

namespace nodaltest
{
/// Every second-order type.
const mp::NodalType AllTypes[] = { mp::NodalType::Edge3, mp::NodalType::Triangle6,
  mp::NodalType::Quad8, mp::NodalType::Quad9, mp::NodalType::Tetra10, mp::NodalType::Hexa20,
  mp::NodalType::Hexa27, mp::NodalType::Wedge15, mp::NodalType::Wedge18, mp::NodalType::Pyramid13 };

/// The type's reference nodes (NodalReferenceNodes), 3 per node.
inline std::vector<double> ReferenceNodes(mp::NodalType type)
{
  std::vector<double> xi(3 * mp::NodalNodeCount(type));
  mp::NodalReferenceNodes(type, xi.data());
  return xi;
}

/// A random point of the reference cell (well inside), widened by `margin`
/// past its faces.
inline void RandomReferencePoint(mp::NodalType type, std::mt19937& rng, double margin, double* xi)
{
  std::uniform_real_distribution<double> u(-margin, 1.0 + margin);
  const int d = mp::NodalCellDimension(type);
  xi[0] = xi[1] = xi[2] = 0.0;
  for (;;)
  {
    for (int a = 0; a < d; ++a)
    {
      xi[a] = u(rng);
    }
    const bool simplex = type == mp::NodalType::Triangle6 || type == mp::NodalType::Tetra10;
    const bool wedge = type == mp::NodalType::Wedge15 || type == mp::NodalType::Wedge18;
    const double sum = simplex ? xi[0] + xi[1] + xi[2] : (wedge ? xi[0] + xi[1] : 0.0);
    const bool apex = type == mp::NodalType::Pyramid13 && xi[2] > 0.9;
    if (sum <= 1.0 + margin && !apex)
    {
      return;
    }
  }
}

/// The corners' (multi)linear functions, written here independently of
/// the kernel: barycentric, products of xi or 1 - xi, triangle times
/// line, and the pyramid's collapsed cube (apex t, base corners (1 - t)).
inline std::vector<double> CornerWeights(mp::NodalType type, const double* xi)
{
  const std::vector<double> nodes = ReferenceNodes(type);
  const int corners = mp::NodalCornerCount(type);
  const int d = mp::NodalCellDimension(type);
  std::vector<double> w(corners, 1.0);
  const bool simplex = type == mp::NodalType::Edge3 || type == mp::NodalType::Triangle6 ||
    type == mp::NodalType::Tetra10;
  const bool wedge = type == mp::NodalType::Wedge15 || type == mp::NodalType::Wedge18;
  for (int c = 0; c < corners; ++c)
  {
    const double* node = &nodes[3 * c];
    if (simplex)
    {
      w[c] = c > 0 ? xi[c - 1] : 1.0;
      for (int a = 0; c == 0 && a < d; ++a)
      {
        w[c] -= xi[a];
      }
    }
    else if (wedge)
    {
      const double l[3] = { 1.0 - xi[0] - xi[1], xi[0], xi[1] };
      w[c] = l[c % 3] * (node[2] == 1.0 ? xi[2] : 1.0 - xi[2]);
    }
    else if (type == mp::NodalType::Pyramid13 && c == 4)
    {
      w[c] = xi[2];
    }
    else
    {
      for (int a = 0; a < (type == mp::NodalType::Pyramid13 ? 3 : d); ++a)
      {
        w[c] *= node[a] == 1.0 ? xi[a] : 1.0 - xi[a];
      }
    }
  }
  return w;
}

/**
 * A straight cell: its corners given (3 per corner), every other node where
 * the corners' map puts its reference point.
 */
inline std::vector<double> StraightCell(mp::NodalType type, const std::vector<double>& corners)
{
  const std::vector<double> nodes = ReferenceNodes(type);
  const int count = mp::NodalNodeCount(type);
  std::vector<double> X(3 * count, 0.0);
  for (int n = 0; n < count; ++n)
  {
    const std::vector<double> w = CornerWeights(type, &nodes[3 * n]);
    for (size_t c = 0; c < w.size(); ++c)
    {
      for (int i = 0; i < 3; ++i)
      {
        X[3 * n + i] += w[c] * corners[3 * c + i];
      }
    }
  }
  return X;
}

/// The reference corners (the pyramid's apex above its base's centre)
/// under x -> A x + b, A = I + 0.3 random (columns beyond the cell's
/// dimension unused), b random; with `jitter`, each corner moved further
/// by up to that much (no longer an affine image).
inline std::vector<double> MappedCorners(mp::NodalType type, std::mt19937& rng, double jitter)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double A[3][3];
  double b[3];
  for (int i = 0; i < 3; ++i)
  {
    b[i] = 5.0 * u(rng);
    for (int j = 0; j < 3; ++j)
    {
      A[i][j] = (i == j ? 1.0 : 0.0) + 0.3 * u(rng);
    }
  }
  const std::vector<double> nodes = ReferenceNodes(type);
  const int corners = mp::NodalCornerCount(type);
  std::vector<double> X(3 * corners);
  for (int c = 0; c < corners; ++c)
  {
    double p[3] = { nodes[3 * c], nodes[3 * c + 1], nodes[3 * c + 2] };
    if (type == mp::NodalType::Pyramid13 && c == 4)
    {
      p[0] = p[1] = 0.5;
    }
    for (int i = 0; i < 3; ++i)
    {
      X[3 * c + i] = b[i] + jitter * u(rng);
      for (int j = 0; j < 3; ++j)
      {
        X[3 * c + i] += A[i][j] * p[j];
      }
    }
  }
  return X;
}

/// sum_n N_n(xi) X_n.
inline void MapPoint(mp::NodalType type, const std::vector<double>& X, const double* xi, double* x)
{
  double N[mp::MaxNodalNodes];
  mp::NodalValues(type, xi, N);
  x[0] = x[1] = x[2] = 0.0;
  for (int n = 0; n < mp::NodalNodeCount(type); ++n)
  {
    for (int i = 0; i < 3; ++i)
    {
      x[i] += N[n] * X[3 * n + i];
    }
  }
}

/// The monomials x^a y^b z^c of total degree <= `degree` in d variables.
} // namespace nodaltest

#endif
