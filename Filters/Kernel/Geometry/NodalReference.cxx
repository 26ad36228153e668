// SPDX-License-Identifier: BSD-3-Clause
// NodalReference and NodalIsStraight (NodalShapes.h): the inverse of the
// isoparametric map, by (Gauss-)Newton on the shape functions.
#include "Geometry/NodalShapes.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mp
{
namespace
{
/// Solves the n x n system A y = b (n <= 3, y into b) by elimination with
/// partial pivoting, and gives A's (signed) determinant; false for a zero
/// pivot.
bool Solve(int n, double A[3][3], double* b, double& determinant)
{
  determinant = 1.0;
  for (int k = 0; k < n; ++k)
  {
    int pivot = k;
    for (int i = k + 1; i < n; ++i)
    {
      pivot = std::abs(A[i][k]) > std::abs(A[pivot][k]) ? i : pivot;
    }
    if (!(std::abs(A[pivot][k]) > 0.0))
    {
      return false;
    }
    determinant *= pivot == k ? A[pivot][k] : -A[pivot][k]; // a swap turns the sign
    std::swap(A[k], A[pivot]);
    std::swap(b[k], b[pivot]);
    for (int i = k + 1; i < n; ++i)
    {
      const double factor = A[i][k] / A[k][k];
      for (int j = k; j < n; ++j)
      {
        A[i][j] -= factor * A[k][j];
      }
      b[i] -= factor * b[k];
    }
  }
  for (int k = n - 1; k >= 0; --k)
  {
    for (int j = k + 1; j < n; ++j)
    {
      b[k] -= A[k][j] * b[j];
    }
    b[k] /= A[k][k];
  }
  return true;
}

/// A cell's nodes relative to its first corner (so that rounding scales
/// with the cell, not with its distance from the origin), and its size.
struct LocalCell
{
  NodalType Type;
  int Dimension;
  int Space;
  int Count;
  double X[MaxNodalNodes][3];
  double Size;
};

/// What the Newton steps read of a cell: its nodes relative to the first
/// corner (LocalCell's, or NodalInverse's), its dimension and its space's.
struct Frame
{
  const double (*X)[3];
  int Dimension;
  int Space;
};

LocalCell MakeLocal(NodalType type, const double* X, int space)
{
  LocalCell cell;
  cell.Type = type;
  cell.Dimension = NodalCellDimension(type);
  cell.Space = space;
  cell.Count = NodalNodeCount(type);
  double lo[3] = { 0.0, 0.0, 0.0 };
  double hi[3] = { 0.0, 0.0, 0.0 };
  for (int n = 0; n < cell.Count; ++n)
  {
    for (int i = 0; i < 3; ++i)
    {
      cell.X[n][i] = i < space ? X[n * 3 + i] - X[i] : 0.0;
      if (n < NodalCornerCount(type))
      {
        lo[i] = std::min(lo[i], cell.X[n][i]);
        hi[i] = std::max(hi[i], cell.X[n][i]);
      }
    }
  }
  cell.Size = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
    (hi[2] - lo[2]) * (hi[2] - lo[2]));
  return cell;
}

/**
 * One (Gauss-)Newton step for sum_n N_n(xi) X_n = x over the first `count`
 * nodes with the functions `shapes` (the corners' or the full ones):
 * step = the least-squares solution of J step = x - x(xi), and J's
 * determinant at xi (det J^T J in space). False when J's columns are
 * dependent (relative 1e-13).
 */
template <typename Shapes>
bool NewtonStep(const Frame& cell, int count, Shapes shapes, const double* x, const double* xi,
  double* step, double& determinant)
{
  double N[MaxNodalNodes];
  double dN[MaxNodalNodes * 3];
  shapes(xi, N, dN);
  double residual[3] = { x[0], x[1], x[2] };
  double J[3][3] = {}; // J[i][a] = dx_i / dxi_a
  for (int n = 0; n < count; ++n)
  {
    for (int i = 0; i < cell.Space; ++i)
    {
      residual[i] -= N[n] * cell.X[n][i];
      for (int a = 0; a < cell.Dimension; ++a)
      {
        J[i][a] += dN[n * 3 + a] * cell.X[n][i];
      }
    }
  }
  const int d = cell.Dimension;
  double A[3][3] = {};
  double b[3] = { 0.0, 0.0, 0.0 };
  double lengths = 1.0; // the product of the columns' lengths
  for (int a = 0; a < d; ++a)
  {
    double length = 0.0;
    for (int i = 0; i < cell.Space; ++i)
    {
      length += J[i][a] * J[i][a];
    }
    lengths *= std::sqrt(length);
  }
  if (cell.Space == d)
  {
    std::copy(&J[0][0], &J[0][0] + 9, &A[0][0]);
    std::copy(residual, residual + 3, b);
  }
  else // the normal equations J^T J step = J^T residual
  {
    for (int a = 0; a < d; ++a)
    {
      for (int c = 0; c < d; ++c)
      {
        for (int i = 0; i < cell.Space; ++i)
        {
          A[a][c] += J[i][a] * J[i][c];
        }
      }
      for (int i = 0; i < cell.Space; ++i)
      {
        b[a] += J[i][a] * residual[i];
      }
    }
  }
  // The volume the columns span against the product of their lengths
  // (1 for orthogonal columns): |det J|, or sqrt(det J^T J) in space.
  if (!Solve(d, A, b, determinant))
  {
    return false;
  }
  const double volume = cell.Space == d ? std::abs(determinant) : std::sqrt(std::abs(determinant));
  if (!(volume > 1e-13 * lengths))
  {
    return false;
  }
  std::copy(b, b + d, step);
  return true;
}

/**
 * Newton iterations from xi: stops at a step below 1e-14 (not applied, so
 * an exact start stays exact), at one below 1e-10 over half the last (the
 * steps no longer shrink: the rounding floor), or after applying one below
 * 1e-9 and 1e-3 times the last (converging quadratically, the next would
 * be below 1e-15); gives the determinant of the last step's J (at or next
 * to the xi returned). False when singular or not
 * converged in 50 steps.
 */
template <typename Shapes>
bool Iterate(
  const Frame& cell, int count, Shapes shapes, const double* x, double* xi, double& determinant)
{
  double previous = HUGE_VAL;
  for (int iteration = 0; iteration < 50; ++iteration)
  {
    double step[3] = { 0.0, 0.0, 0.0 };
    if (!NewtonStep(cell, count, shapes, x, xi, step, determinant))
    {
      return false;
    }
    double size = 0.0;
    for (int a = 0; a < cell.Dimension; ++a)
    {
      size = std::max(size, std::abs(step[a]));
    }
    if (size <= 1e-14 || (size <= 1e-10 && size > 0.5 * previous))
    {
      return true;
    }
    for (int a = 0; a < cell.Dimension; ++a)
    {
      xi[a] += step[a];
    }
    if (size <= 1e-9 && size <= 1e-3 * previous)
    {
      // Quadratic convergence: the next step would be about size^2 / previous
      // (below 1e-15); J is that of the point before, hence the determinant
      // is nearly that at xi.
      return true;
    }
    previous = size;
  }
  return false;
}

/// The full map's functions of `type` (NodalValuesAndDerivatives).
struct FullShapes
{
  NodalType Type;
  void operator()(const double* p, double* N, double* dN) const
  {
    NodalValuesAndDerivatives(this->Type, p, N, dN);
  }
};

/// The corners' functions of `type` (NodalCornerFunctions).
struct CornerShapes
{
  NodalType Type;
  void operator()(const double* p, double* N, double* dN) const
  {
    NodalCornerFunctions(this->Type, p, N, dN);
  }
};
} // namespace

bool NodalReference(
  NodalType type, const double* X, int spaceDimension, const double* x, double* xi)
{
  NodalInverse inverse;
  if (!inverse.Prepare(type, X, spaceDimension))
  {
    xi[0] = xi[1] = xi[2] = 0.0;
    return false;
  }
  return inverse.FindFromCentre(x, xi);
}

bool NodalInverse::Prepare(NodalType type, const double* X, int spaceDimension)
{
  const int d = NodalCellDimension(type);
  this->Type = NodalType::None;
  if (d == 0 || spaceDimension < d || spaceDimension > 3)
  {
    return false;
  }
  this->Type = type;
  this->Dimension = d;
  this->Space = spaceDimension;
  this->Count = NodalNodeCount(type);
  const LocalCell cell = MakeLocal(type, X, spaceDimension);
  std::copy(&cell.X[0][0], &cell.X[0][0] + 3 * MaxNodalNodes, &this->X[0][0]);
  for (int i = 0; i < 3; ++i)
  {
    this->Origin[i] = i < spaceDimension ? X[i] : 0.0;
  }
  // The reference cell's centre (a corner's simplex: one step from it is
  // the affine solve).
  double nodes[MaxNodalNodes * 3];
  NodalReferenceNodes(type, nodes);
  const int corners = NodalCornerCount(type);
  std::fill(this->Centre, this->Centre + 3, 0.0);
  for (int n = 0; n < corners; ++n)
  {
    for (int a = 0; a < d; ++a)
    {
      this->Centre[a] += nodes[n * 3 + a] / corners;
    }
  }
  if (type == NodalType::Pyramid13)
  {
    this->Centre[0] = this->Centre[1] = 0.5; // the apex's (0, 0) is one of its points
  }
  this->Straight = NodalIsStraight(type, X, spaceDimension, 1e-12);
  // The cell's orientation: the corners' map's Jacobian at the centre (0
  // where it is singular: no fold check).
  const Frame frame{ this->X, d, spaceDimension };
  const double zero[3] = { 0.0, 0.0, 0.0 };
  double step[3];
  if (!NewtonStep(
        frame, corners, CornerShapes{ type }, zero, this->Centre, step, this->Orientation))
  {
    this->Orientation = 0.0;
  }
  return true;
}

bool NodalInverse::Local(const double* x, double* local) const
{
  local[0] = local[1] = local[2] = 0.0;
  if (this->Type == NodalType::None)
  {
    return false;
  }
  for (int i = 0; i < this->Space; ++i)
  {
    local[i] = x[i] - this->Origin[i];
  }
  return true;
}

bool NodalInverse::Converge(const double* local, double* xi) const
{
  const Frame frame{ this->X, this->Dimension, this->Space };
  double determinant = 0.0; // the full map's, at the xi returned
  if (!Iterate(frame, this->Count, FullShapes{ this->Type }, local, xi, determinant))
  {
    return false;
  }
  // On the cell's own sheet only: past a fold of the extrapolated map (or
  // inside an inverted cell) the map turns the other way round.
  return this->Space > this->Dimension || this->Orientation == 0.0 ||
    this->Orientation * determinant > 0.0;
}

bool NodalInverse::Find(const double* x, const double* start, double* xi) const
{
  double local[3];
  xi[0] = xi[1] = xi[2] = 0.0;
  if (!this->Local(x, local))
  {
    return false;
  }
  std::copy(start, start + this->Dimension, xi);
  if (this->Straight)
  {
    // The map is the corners' (multi)linear one: its cheaper steps first,
    // then the full map's (a step or two to confirm).
    const Frame frame{ this->X, this->Dimension, this->Space };
    double ignored = 0.0;
    if (!Iterate(
          frame, NodalCornerCount(this->Type), CornerShapes{ this->Type }, local, xi, ignored))
    {
      std::copy(start, start + this->Dimension, xi);
    }
  }
  if (!this->Converge(local, xi))
  {
    return false;
  }
  for (int a = 0; a < this->Dimension; ++a)
  {
    if (std::abs(xi[a] - start[a]) > FindReach)
    {
      return false;
    }
  }
  return true;
}

bool NodalInverse::FindFromCentre(const double* x, double* xi) const
{
  double local[3];
  xi[0] = xi[1] = xi[2] = 0.0;
  if (!this->Local(x, local))
  {
    return false;
  }
  const int d = this->Dimension;
  const Frame frame{ this->X, d, this->Space };
  // The corners' map: on a simplex it is affine and the first step from
  // the centre inverts it; otherwise Newton goes on (from the centre again
  // if it fails). Its Jacobian at the centre orients the cell.
  double orientation = 0.0;
  double step[3] = { 0.0, 0.0, 0.0 };
  std::copy(this->Centre, this->Centre + 3, xi);
  if (NewtonStep(frame, NodalCornerCount(this->Type), CornerShapes{ this->Type }, local,
        this->Centre, step, orientation))
  {
    for (int a = 0; a < d; ++a)
    {
      xi[a] += step[a];
    }
    const NodalType type = this->Type;
    const bool simplex =
      type == NodalType::Edge3 || type == NodalType::Triangle6 || type == NodalType::Tetra10;
    double ignored = 0.0;
    if (!simplex &&
      !Iterate(frame, NodalCornerCount(type), CornerShapes{ type }, local, xi, ignored))
    {
      std::copy(this->Centre, this->Centre + 3, xi);
    }
  }
  double determinant = 0.0; // the full map's, at the xi returned
  if (!Iterate(frame, this->Count, FullShapes{ this->Type }, local, xi, determinant))
  {
    return false;
  }
  return this->Space > d || orientation == 0.0 || orientation * determinant > 0.0;
}

bool NodalIsStraight(NodalType type, const double* X, int spaceDimension, double tolerance)
{
  if (NodalCellDimension(type) == 0)
  {
    return true;
  }
  const LocalCell cell = MakeLocal(type, X, spaceDimension);
  double nodes[MaxNodalNodes * 3];
  NodalReferenceNodes(type, nodes);
  const int corners = NodalCornerCount(type);
  const double bound = tolerance * cell.Size;
  for (int n = corners; n < cell.Count; ++n)
  {
    double N[8];
    NodalCornerFunctions(type, nodes + 3 * n, N, nullptr);
    double distance2 = 0.0;
    for (int i = 0; i < spaceDimension; ++i)
    {
      double linear = 0.0;
      for (int c = 0; c < corners; ++c)
      {
        linear += N[c] * cell.X[c][i];
      }
      distance2 += (cell.X[n][i] - linear) * (cell.X[n][i] - linear);
    }
    if (!(std::sqrt(distance2) <= bound))
    {
      return false;
    }
  }
  return true;
}
} // namespace mp
