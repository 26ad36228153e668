// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/HiddenNodes.h"

#include <algorithm>
#include <cmath>

namespace mp
{
namespace
{
/// A face of a reference cell: the points with Coefficient . xi = Value.
struct ReferenceFace
{
  double Coefficient[3];
  double Value;
};

const ReferenceFace QuadFaces[] = { { { 1, 0, 0 }, 0 }, { { 1, 0, 0 }, 1 }, { { 0, 1, 0 }, 0 },
  { { 0, 1, 0 }, 1 } };
const ReferenceFace HexaFaces[] = { { { 1, 0, 0 }, 0 }, { { 1, 0, 0 }, 1 }, { { 0, 1, 0 }, 0 },
  { { 0, 1, 0 }, 1 }, { { 0, 0, 1 }, 0 }, { { 0, 0, 1 }, 1 } };
const ReferenceFace WedgeFaces[] = { { { 1, 0, 0 }, 0 }, { { 0, 1, 0 }, 0 }, { { 1, 1, 0 }, 1 },
  { { 0, 0, 1 }, 0 }, { { 0, 0, 1 }, 1 } };

bool OnFace(const ReferenceFace& f, const double* xi)
{
  const double v = f.Coefficient[0] * xi[0] + f.Coefficient[1] * xi[1] + f.Coefficient[2] * xi[2];
  return std::fabs(v - f.Value) < 1e-12;
}

/**
 * The nodes of the cell that a hidden node's value depends on: those on
 * every reference face the hidden node lies on (all of them for a node
 * inside). Their count; `support` gets their numbers.
 */
int HiddenSupport(NodalType type, const double* reference, int hidden, int* support)
{
  const ReferenceFace* faces = QuadFaces;
  int count = 4;
  if (type == NodalType::Hexa20)
  {
    faces = HexaFaces, count = 6;
  }
  else if (type == NodalType::Wedge15)
  {
    faces = WedgeFaces, count = 5;
  }
  const double* xh = reference + 3 * hidden;
  int n = 0;
  for (int node = 0; node < NodalNodeCount(type); ++node)
  {
    bool on = true;
    for (int f = 0; f < count && on; ++f)
    {
      on = !OnFace(faces[f], xh) || OnFace(faces[f], reference + 3 * node);
    }
    if (on)
    {
      support[n++] = node;
    }
  }
  return n;
}

/// The monomials of degree <= 2 of y (d coordinates): 1, the d linear ones,
/// then the products y_a y_b (a <= b); their count.
int Monomials(int d, const double* y, double* m)
{
  int k = 0;
  m[k++] = 1.0;
  for (int a = 0; a < d; ++a)
  {
    m[k++] = y[a];
  }
  for (int a = 0; a < d; ++a)
  {
    for (int b = a; b < d; ++b)
    {
      m[k++] = y[a] * y[b];
    }
  }
  return k;
}

constexpr int MaxMonomials = 10;

/// A linear column left, after its part along the columns before it is
/// taken off, with less than this much of its length, carries no
/// constraint of its own (a coordinate constant or affine in the others).
/// A quadratic column left shorter than this (the coordinates scaled to
/// the nodes' extent, per node) carries none either: a constraint nearly
/// dependent on the others would make the weights huge. A face's normal
/// coordinate that varies less than NormalFloor is taken as 0 (a planar
/// face).
constexpr double LinearDependence = 1e-12;
constexpr double QuadraticDependence = 1e-6;
constexpr double NormalFloor = 1e-12;

double SquaredLength(const double* v, int count)
{
  double sum = 0.0;
  for (int k = 0; k < count; ++k)
  {
    sum += v[k] * v[k];
  }
  return sum;
}

/// v -= (q_i . v) q_i for the first `kept` unit columns q_i of `basis`
/// (the dot products over the nodes; the hidden value, entry `count`,
/// follows).
void SubtractProjections(const double (*basis)[MaxHiddenOwners + 1], int kept, int count, double* v)
{
  for (int i = 0; i < kept; ++i)
  {
    double r = 0.0;
    for (int k = 0; k < count; ++k)
    {
      r += basis[i][k] * v[k];
    }
    for (int k = 0; k <= count; ++k)
    {
      v[k] -= r * basis[i][k];
    }
  }
}

/**
 * The principal axes of `count` points (3 coordinates each) about their
 * centre: axes[0], axes[1], axes[2] unit and orthogonal, by decreasing
 * spread (axes[2]: a face's normal). Cyclic Jacobi on the 3 x 3 scatter
 * matrix.
 */
void PrincipalAxes(int count, const double* P, const double* centre, double (&axes)[3][3])
{
  double a[3][3] = {};
  for (int k = 0; k < count; ++k)
  {
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        a[r][c] += (P[3 * k + r] - centre[r]) * (P[3 * k + c] - centre[c]);
      }
    }
  }
  double v[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } }; // columns: the vectors
  for (int sweep = 0; sweep < 50; ++sweep)
  {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diagonal = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (!(off > 1e-32 * diagonal))
    {
      break;
    }
    for (int p = 0; p < 2; ++p)
    {
      for (int q = p + 1; q < 3; ++q)
      {
        if (a[p][q] == 0.0)
        {
          continue;
        }
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t =
          (theta >= 0.0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 3; ++k) // A <- A J, then A <- J^T A, V <- V J
        {
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k)
        {
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k)
        {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  int order[3] = { 0, 1, 2 };
  std::sort(order, order + 3, [&a](int i, int j) { return a[i][i] > a[j][j]; });
  for (int i = 0; i < 3; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      axes[i][k] = v[k][order[i]];
    }
  }
}

/**
 * Gram-Schmidt (twice where needed) over the columns of `columns` (rows:
 * the count nodes, then the hidden node), the first `linear` ones the
 * linear monomials: each quadratic column left independent adds its unit
 * column times its constraint's residual to w. Returns how many linear
 * columns were kept (they are basis[0 ..]).
 */
int Correct(const double (*columns)[MaxMonomials], int count, int monomials, int linear,
  double (*basis)[MaxHiddenOwners + 1], double* w)
{
  int kept = 0, keptLinear = 0;
  for (int j = 0; j < monomials; ++j)
  {
    double v[MaxHiddenOwners + 1];
    for (int k = 0; k <= count; ++k)
    {
      v[k] = columns[k][j];
    }
    const double length = SquaredLength(v, count);
    // A second pass only where the first cancelled much of the column
    // (where rounding leaves it off orthogonal): "twice is enough".
    double left = length;
    for (int pass = 0; pass < 2 && kept > 0; ++pass)
    {
      const double before = left;
      SubtractProjections(basis, kept, count, v);
      left = SquaredLength(v, count);
      if (left > 0.25 * before)
      {
        break;
      }
    }
    const bool isLinear = j < linear;
    const double floor = isLinear ? LinearDependence * LinearDependence * length
                                  : QuadraticDependence * QuadraticDependence * count;
    if (!(left > floor))
    {
      continue;
    }
    const double scale = 1.0 / std::sqrt(left);
    for (int k = 0; k <= count; ++k)
    {
      basis[kept][k] = v[k] * scale;
    }
    if (!isLinear)
    {
      double residual = basis[kept][count];
      for (int k = 0; k < count; ++k)
      {
        residual -= basis[kept][k] * w[k];
      }
      for (int k = 0; k < count; ++k)
      {
        w[k] += residual * basis[kept][k];
      }
    }
    keptLinear += isLinear;
    ++kept;
  }
  return keptLinear;
}

/**
 * The weights of one hidden node over `count` nodes (their coordinates P,
 * 3 per node, d read), from the serendipity weights s: w = s + the
 * smallest change that makes sum_k w_k p(P_k) = p(x_h) for every
 * quadratic monomial p (x_h = sum_k s_k P_k, the cell's own map at the
 * hidden node's reference point) while keeping the linear ones as s has
 * them (Correct). The coordinates are centred on the nodes and scaled by
 * their extent. A face (8 nodes in 3D) is taken in its principal axes:
 * the quadratic monomials of its two in-plane coordinates only, and the
 * change then made orthogonal to the normal coordinate too, so that
 * linear fields stay exact on a curved or twisted face while the
 * in-plane problem stays well conditioned (a normal coordinate nearly
 * affine in the others would make its quadratic constraints nearly
 * dependent and the weights huge).
 */
void CorrectedWeights(int count, const double* P, int d, const double* s, double* w)
{
  double centre[3] = {};
  for (int k = 0; k < count; ++k)
  {
    for (int a = 0; a < d; ++a)
    {
      centre[a] += P[3 * k + a];
    }
  }
  double size = 0.0;
  for (int a = 0; a < d; ++a)
  {
    centre[a] /= count;
    for (int k = 0; k < count; ++k)
    {
      size = std::max(size, std::fabs(P[3 * k + a] - centre[a]));
    }
  }
  std::copy(s, s + count, w);
  if (!(size > 0.0))
  {
    return;
  }
  const bool face = d == 3 && count == 8;
  double axes[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  if (face)
  {
    PrincipalAxes(count, P, centre, axes);
  }
  const int m = face ? 2 : d; // the coordinates of the monomials
  // Row k of `columns`: the monomials at node k; row `count`: at x_h.
  double columns[MaxHiddenOwners + 1][MaxMonomials];
  double normal[MaxHiddenOwners];
  double hidden[3] = {};
  int monomials = 0;
  for (int k = 0; k < count; ++k)
  {
    double y[3];
    for (int a = 0; a < d; ++a)
    {
      y[a] = 0.0;
      for (int b = 0; b < d; ++b)
      {
        y[a] += axes[a][b] * (P[3 * k + b] - centre[b]);
      }
      y[a] /= size;
      hidden[a] += s[k] * y[a];
    }
    normal[k] = y[2];
    monomials = Monomials(m, y, columns[k]);
  }
  Monomials(m, hidden, columns[count]);
  double basis[MaxMonomials][MaxHiddenOwners + 1];
  const int linear = Correct(columns, count, monomials, m + 1, basis, w);
  if (!face)
  {
    return;
  }
  // The normal coordinate's part off the in-plane linear columns; the
  // change made orthogonal to it (it stays orthogonal to them).
  double v[MaxHiddenOwners + 1] = {};
  std::copy(normal, normal + count, v);
  SubtractProjections(basis, linear, count, v);
  SubtractProjections(basis, linear, count, v);
  const double left = SquaredLength(v, count);
  if (!(left > NormalFloor * NormalFloor * count))
  {
    return; // a planar face
  }
  double along = 0.0;
  for (int k = 0; k < count; ++k)
  {
    along += v[k] * (w[k] - s[k]);
  }
  for (int k = 0; k < count; ++k)
  {
    w[k] -= along / left * v[k];
  }
}

/// A type's hidden nodes: how many, the nodes each depends on
/// (HiddenSupport) and the serendipity weights there, N_n(xi_h).
struct HiddenLayout
{
  int Hidden = 0;
  int Count[MaxHiddenNodes] = {};
  int Support[MaxHiddenNodes][MaxHiddenOwners] = {};
  double Serendipity[MaxHiddenNodes][MaxNodalNodes] = {};
};

HiddenLayout MakeLayout(NodalType type)
{
  HiddenLayout layout;
  const NodalType sibling = CompleteSibling(type);
  const int own = NodalNodeCount(type);
  double reference[3 * MaxNodalNodes];
  NodalReferenceNodes(sibling, reference);
  layout.Hidden = NodalNodeCount(sibling) - own;
  for (int h = 0; h < layout.Hidden; ++h)
  {
    layout.Count[h] = HiddenSupport(type, reference, own + h, layout.Support[h]);
    NodalValues(type, reference + 3 * (own + h), layout.Serendipity[h]);
  }
  return layout;
}

/// The layout of Quad8, Hexa20 or Wedge15, made once.
const HiddenLayout& LayoutOf(NodalType type)
{
  static const HiddenLayout quad = MakeLayout(NodalType::Quad8);
  static const HiddenLayout hexa = MakeLayout(NodalType::Hexa20);
  static const HiddenLayout wedge = MakeLayout(NodalType::Wedge15);
  return type == NodalType::Quad8 ? quad : (type == NodalType::Hexa20 ? hexa : wedge);
}
} // namespace

NodalType CompleteSibling(NodalType type)
{
  switch (type)
  {
    case NodalType::Quad8:
      return NodalType::Quad9;
    case NodalType::Hexa20:
      return NodalType::Hexa27;
    case NodalType::Wedge15:
      return NodalType::Wedge18;
    default:
      return NodalType::None;
  }
}

void HiddenNodeWeights(
  NodalType type, const double* X, const Index* ids, int spaceDimension, double* W)
{
  const HiddenLayout& layout = LayoutOf(type);
  const int own = NodalNodeCount(type);
  std::fill(W, W + layout.Hidden * own, 0.0);
  for (int h = 0; h < layout.Hidden; ++h)
  {
    // The face's nodes in the order of their ids: both cells on it
    // combine the same numbers in the same order.
    const int count = layout.Count[h];
    int support[MaxHiddenOwners];
    std::copy(layout.Support[h], layout.Support[h] + count, support);
    std::sort(support, support + count,
      [ids](int a, int b) { return ids[a] < ids[b] || (ids[a] == ids[b] && a < b); });
    double P[3 * MaxHiddenOwners], s[MaxHiddenOwners], w[MaxHiddenOwners];
    for (int k = 0; k < count; ++k)
    {
      std::copy(X + 3 * support[k], X + 3 * support[k] + 3, P + 3 * k);
      s[k] = layout.Serendipity[h][support[k]];
    }
    CorrectedWeights(count, P, spaceDimension, s, w);
    for (int k = 0; k < count; ++k)
    {
      W[h * own + support[k]] = w[k];
    }
  }
}

void HiddenNodeFunctions(NodalType type, const double* W, const double* xi, double* phi)
{
  const NodalType sibling = CompleteSibling(type);
  const int own = NodalNodeCount(type);
  const int hidden = NodalNodeCount(sibling) - own;
  double M[MaxNodalNodes];
  NodalValues(sibling, xi, M);
  for (int n = 0; n < own; ++n)
  {
    double v = M[n];
    for (int h = 0; h < hidden; ++h)
    {
      v += W[h * own + n] * M[own + h];
    }
    phi[n] = v;
  }
}
} // namespace mp
