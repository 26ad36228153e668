// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/Predicates.h"

#include <cmath>
#include <limits>

namespace mp
{
namespace
{
// Error-free transformations: a + b == s + e and a * b == p + e exactly.
inline void TwoSum(double a, double b, double& s, double& e)
{
  s = a + b;
  const double bv = s - a;
  const double av = s - bv;
  e = (a - av) + (b - bv);
}

inline void TwoProduct(double a, double b, double& p, double& e)
{
  p = a * b;
  e = std::fma(a, b, -p);
}

inline void TwoDiff(double a, double b, double& d, double& e)
{
  d = a - b;
  const double bv = a - d;
  const double av = d + bv;
  e = (a - av) + (bv - b);
}

/// A small floating-point expansion: nonoverlapping components in
/// increasing magnitude, zeros removed; its value is their exact sum.
struct Expansion
{
  static constexpr int Capacity = 256;
  double H[Capacity];
  int N = 0;

  void Add(double b)
  {
    if (b == 0.0)
    {
      return;
    }
    double q = b;
    int m = 0;
    for (int i = 0; i < this->N; ++i)
    {
      double s;
      double e;
      TwoSum(q, this->H[i], s, e);
      if (e != 0.0)
      {
        this->H[m++] = e;
      }
      q = s;
    }
    if (q != 0.0)
    {
      this->H[m++] = q;
    }
    this->N = m;
  }
  void Add(const Expansion& e)
  {
    for (int i = 0; i < e.N; ++i)
    {
      this->Add(e.H[i]);
    }
  }
  /// this += a * b, exactly.
  void AddProduct(const Expansion& a, const Expansion& b)
  {
    for (int i = 0; i < a.N; ++i)
    {
      for (int j = 0; j < b.N; ++j)
      {
        double p;
        double e;
        TwoProduct(a.H[i], b.H[j], p, e);
        this->Add(e);
        this->Add(p);
      }
    }
  }
  void Negate()
  {
    for (int i = 0; i < this->N; ++i)
    {
      this->H[i] = -this->H[i];
    }
  }
  double Estimate() const
  {
    double sum = 0.0;
    for (int i = 0; i < this->N; ++i)
    {
      sum += this->H[i];
    }
    return sum;
  }
  int Sign() const { return this->N == 0 ? 0 : (this->H[this->N - 1] > 0.0 ? 1 : -1); }
};

/// The exact difference a - b as an expansion of at most two components.
inline Expansion Difference(double a, double b)
{
  Expansion e;
  double d;
  double t;
  TwoDiff(a, b, d, t);
  e.Add(t);
  e.Add(d);
  return e;
}

/// A value whose sign is that of the expansion and whose magnitude is close to it.
inline double SignedEstimate(const Expansion& e)
{
  const int sign = e.Sign();
  if (sign == 0)
  {
    return 0.0;
  }
  const double estimate = e.Estimate();
  return (estimate != 0.0 && (estimate > 0.0) == (sign > 0))
    ? estimate
    : std::copysign(std::numeric_limits<double>::denorm_min(), double(sign));
}
} // namespace

double Orient3DExact(const double* a, const double* b, const double* c, const double* d)
{
  // det[b - a, c - a, d - a] with every difference kept exact.
  Expansion u[3];
  Expansion v[3];
  Expansion w[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = Difference(b[k], a[k]);
    v[k] = Difference(c[k], a[k]);
    w[k] = Difference(d[k], a[k]);
  }
  Expansion det;
  for (int k = 0; k < 3; ++k)
  {
    // u[k] * (v[k+1] w[k+2] - v[k+2] w[k+1])
    Expansion minor;
    minor.AddProduct(v[(k + 1) % 3], w[(k + 2) % 3]);
    Expansion other;
    other.AddProduct(v[(k + 2) % 3], w[(k + 1) % 3]);
    other.Negate();
    minor.Add(other);
    det.AddProduct(u[k], minor);
  }
  return SignedEstimate(det);
}

namespace
{
/// Whether three points share two coordinates: then they lie on one line
/// parallel to an axis, exactly.
bool OnAxisLine(const double* a, const double* b, const double* c)
{
  const bool same[3] = { a[0] == b[0] && a[0] == c[0], a[1] == b[1] && a[1] == c[1],
    a[2] == b[2] && a[2] == c[2] };
  return (same[0] && same[1]) || (same[0] && same[2]) || (same[1] && same[2]);
}

/**
 * Configurations whose orientation is exactly zero for a reason that shows
 * without arithmetic, common in structured and shared boundaries: a
 * coordinate shared by all four points (a coordinate plane, e.g. the face
 * of a box: every term of the determinant holds one difference of each
 * coordinate), two equal points, or three on one axis-parallel line.
 */
bool TriviallyCoplanar(const double* a, const double* b, const double* c, const double* d)
{
  const double* p[4] = { a, b, c, d };
  for (int k = 0; k < 3; ++k)
  {
    if (b[k] == a[k] && c[k] == a[k] && d[k] == a[k])
    {
      return true;
    }
  }
  for (int i = 0; i < 4; ++i)
  {
    for (int j = i + 1; j < 4; ++j)
    {
      if (p[i][0] == p[j][0] && p[i][1] == p[j][1] && p[i][2] == p[j][2])
      {
        return true;
      }
    }
  }
  return OnAxisLine(a, b, c) || OnAxisLine(a, b, d) || OnAxisLine(a, c, d) || OnAxisLine(b, c, d);
}
} // namespace

double Orient3D(const double* a, const double* b, const double* c, const double* d)
{
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
  const double m0 = vy * wz - vz * wy;
  const double m1 = vz * wx - vx * wz;
  const double m2 = vx * wy - vy * wx;
  const double det = ux * m0 + uy * m1 + uz * m2;
  const double permanent = std::fabs(ux) * (std::fabs(vy * wz) + std::fabs(vz * wy)) +
    std::fabs(uy) * (std::fabs(vz * wx) + std::fabs(vx * wz)) +
    std::fabs(uz) * (std::fabs(vx * wy) + std::fabs(vy * wx));
  // The differences are rounded too, hence a bound a little wider than
  // Shewchuk's for exact differences: 8 eps covers both.
  if (std::fabs(det) > 8.0 * RoundingUnit * permanent)
  {
    return det;
  }
  if (TriviallyCoplanar(a, b, c, d))
  {
    return 0.0;
  }
  if (permanent == 0.0)
  {
    // Every product of the differences is zero. When the differences are
    // exact, so is the determinant: no expansions needed.
    bool exact = true;
    for (int k = 0; k < 3; ++k)
    {
      double diff;
      double tail;
      TwoDiff(b[k], a[k], diff, tail);
      exact &= tail == 0.0;
      TwoDiff(c[k], a[k], diff, tail);
      exact &= tail == 0.0;
      TwoDiff(d[k], a[k], diff, tail);
      exact &= tail == 0.0;
    }
    if (exact)
    {
      return 0.0;
    }
  }
  return Orient3DExact(a, b, c, d);
}

double Orient2DExact(const double* a, const double* b, const double* c)
{
  // (ax - cx)(by - cy) - (ay - cy)(bx - cx) expanded into six products of
  // input coordinates (the cx*cy terms cancel), each split exactly in two.
  const double factors[6][2] = { { a[0], b[1] }, { -a[0], c[1] }, { -c[0], b[1] }, { -a[1], b[0] },
    { a[1], c[0] }, { c[1], b[0] } };
  Expansion det;
  for (const auto& f : factors)
  {
    double p;
    double e;
    TwoProduct(f[0], f[1], p, e);
    det.Add(e);
    det.Add(p);
  }
  return SignedEstimate(det);
}
} // namespace mp
