// SPDX-License-Identifier: BSD-3-Clause
#include "Transfer/BernsteinForm.h"

#include "Geometry/NodalShapes.h"

#include <algorithm>
#include <cmath>

namespace mp
{
namespace
{
/// How a type's Bernstein functions are made: in barycentric coordinates,
/// as tensor products of the 1D ones, or the triangle's times the 1D ones.
enum class Family
{
  Simplex,
  Tensor,
  Wedge
};

Family FamilyOf(NodalType type)
{
  switch (type)
  {
    case NodalType::Quad9:
    case NodalType::Hexa27:
      return Family::Tensor;
    case NodalType::Wedge18:
      return Family::Wedge;
    default:
      return Family::Simplex;
  }
}

/// The 1D Bernstein function i (0, 1, 2) of degree 2 at t.
double Bernstein1D(int i, double t)
{
  return i == 0 ? (1 - t) * (1 - t) : (i == 1 ? 2 * t * (1 - t) : t * t);
}

/// Twice a reference coordinate of a node (0, 1 or 2: where it sits on [0, 1]).
int Twice(double xi)
{
  return static_cast<int>(std::lround(2 * xi));
}

/**
 * Bernstein function of degree 2 on the simplex of `corners` corners
 * whose barycentric coordinates at the node are those of `node` (reference
 * coordinates), at the point of barycentric coordinates `lambda`; with
 * `dimension` the dimension of what the node stands for (0 corner, 1 edge).
 */
double SimplexBernstein(const double* node, int corners, const double* lambda, int* dimension)
{
  double at[4];
  at[0] = 1.0;
  for (int a = 1; a < corners; ++a)
  {
    at[a] = node[a - 1];
    at[0] -= node[a - 1];
  }
  double value = 1.0;
  int nonzero = 0;
  for (int a = 0; a < corners; ++a)
  {
    const int alpha = Twice(at[a]);
    if (alpha == 2)
    {
      value *= lambda[a] * lambda[a];
    }
    else if (alpha == 1)
    {
      value *= nonzero == 0 ? 2 * lambda[a] : lambda[a];
    }
    nonzero += alpha != 0;
  }
  if (dimension)
  {
    *dimension = nonzero - 1;
  }
  return value;
}

/// The barycentric coordinates of reference point xi on a simplex of `corners` corners.
void Barycentric(const double* xi, int corners, double* lambda)
{
  lambda[0] = 1.0;
  for (int a = 1; a < corners; ++a)
  {
    lambda[a] = xi[a - 1];
    lambda[0] -= xi[a - 1];
  }
}

/// Bernstein function of node `node` (reference coordinates) of `type` at
/// xi, and the dimension of what the node stands for.
double NodeBernstein(NodalType type, const double* node, const double* xi, int* dimension)
{
  const int d = NodalCellDimension(type);
  double lambda[4];
  switch (FamilyOf(type))
  {
    case Family::Tensor:
    {
      double value = 1.0;
      int middle = 0;
      for (int a = 0; a < d; ++a)
      {
        const int i = Twice(node[a]);
        value *= Bernstein1D(i, xi[a]);
        middle += i == 1;
      }
      *dimension = middle;
      return value;
    }
    case Family::Wedge:
    {
      Barycentric(xi, 3, lambda);
      const int i = Twice(node[2]);
      const double value = SimplexBernstein(node, 3, lambda, dimension) * Bernstein1D(i, xi[2]);
      *dimension += i == 1;
      return value;
    }
    default:
      Barycentric(xi, d + 1, lambda);
      return SimplexBernstein(node, d + 1, lambda, dimension);
  }
}

/// One type's C (Bernstein function m at node n) and its nodes' dimensions.
struct TypeTable
{
  int Count = 0;
  double At[MaxNodalNodes][MaxNodalNodes] = {};
  int Dimension[MaxNodalNodes] = {};
};

/// The corners of each mid-edge node of the serendipity types and the
/// pyramid (VTK's order: the edges after the corners).
struct EdgeTable
{
  int Corners = 0;
  int Edges = 0;
  const int (*Ends)[2] = nullptr;
};

const int QuadEdges[4][2] = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 } };
const int HexaEdges[12][2] = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 4, 5 }, { 5, 6 }, { 6, 7 },
  { 7, 4 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
const int WedgeEdges[9][2] = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 3, 4 }, { 4, 5 }, { 5, 3 }, { 0, 3 },
  { 1, 4 }, { 2, 5 } };
const int PyramidEdges[8][2] = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 4 }, { 1, 4 },
  { 2, 4 }, { 3, 4 } };

EdgeTable EdgesOf(NodalType type)
{
  switch (type)
  {
    case NodalType::Quad8:
      return { 4, 4, QuadEdges };
    case NodalType::Hexa20:
      return { 8, 12, HexaEdges };
    case NodalType::Wedge15:
      return { 6, 9, WedgeEdges };
    default:
      return { 5, 8, PyramidEdges };
  }
}

/**
 * C of a serendipity type or the pyramid: a corner's row is itself, a
 * mid-edge node's s (b_a + b_b) + (1 - 2 s) b_e, s its EdgeShare.
 */
void MakeSerendipityTable(NodalType type, TypeTable& table)
{
  const EdgeTable edges = EdgesOf(type);
  const double share = BernsteinForm::EdgeShare(type);
  table.Count = edges.Corners + edges.Edges;
  for (int a = 0; a < edges.Corners; ++a)
  {
    table.At[a][a] = 1.0;
  }
  for (int e = 0; e < edges.Edges; ++e)
  {
    const int n = edges.Corners + e;
    table.At[n][edges.Ends[e][0]] = share;
    table.At[n][edges.Ends[e][1]] = share;
    table.At[n][n] = 1.0 - 2.0 * share;
    table.Dimension[n] = 1;
  }
}

void MakeTable(NodalType type, TypeTable& table)
{
  if (BernsteinForm::Signed(type))
  {
    MakeSerendipityTable(type, table);
    return;
  }
  double xi[3 * MaxNodalNodes];
  NodalReferenceNodes(type, xi);
  table.Count = NodalNodeCount(type);
  for (int n = 0; n < table.Count; ++n)
  {
    for (int m = 0; m < table.Count; ++m)
    {
      int dimension = 0;
      table.At[n][m] = NodeBernstein(type, xi + 3 * m, xi + 3 * n, &dimension);
      if (m == n)
      {
        table.Dimension[n] = dimension;
      }
    }
  }
}

/// A sum that depends on the terms only, not on their order: the terms
/// sorted first (by insertion: at most 27, and no comparison can fail).
double SortedSum(double* terms, int count)
{
  for (int i = 1; i < count; ++i)
  {
    const double t = terms[i];
    int j = i;
    while (j > 0 && terms[j - 1] > t)
    {
      terms[j] = terms[j - 1];
      --j;
    }
    terms[j] = t;
  }
  double sum = 0.0;
  for (int i = 0; i < count; ++i)
  {
    sum += terms[i];
  }
  return sum;
}
} // namespace

bool BernsteinForm::Supports(NodalType type)
{
  switch (type)
  {
    case NodalType::None:
    case NodalType::Edge3:
    case NodalType::Triangle6:
    case NodalType::Tetra10:
    case NodalType::Quad9:
    case NodalType::Hexa27:
    case NodalType::Wedge18:
    case NodalType::Quad8:
    case NodalType::Hexa20:
    case NodalType::Wedge15:
    case NodalType::Pyramid13:
      return true;
    default:
      return false;
  }
}

bool BernsteinForm::Signed(NodalType type)
{
  switch (type)
  {
    case NodalType::Quad8:
    case NodalType::Hexa20:
    case NodalType::Wedge15:
    case NodalType::Pyramid13:
      return true;
    default:
      return false;
  }
}

double BernsteinForm::EdgeShare(NodalType type)
{
  return type == NodalType::Quad8 || type == NodalType::Hexa20 || type == NodalType::Wedge15
    ? 0.4375
    : 0.25;
}

int BernsteinForm::EdgeShares(const MeshView& mesh)
{
  int shares = 0;
  const Index parents = mesh.Nodal ? mesh.Parents() : 0;
  for (Index p = 0; p < parents; ++p)
  {
    const NodalType type = mesh.Nodal->Type[p];
    if (type != NodalType::None)
    {
      shares |= EdgeShare(type) == 0.25 ? QuarterShare : SevenSixteenthsShare;
    }
  }
  return shares;
}

bool BernsteinForm::Covers(const MeshView& mesh)
{
  if (!mesh.Nodal)
  {
    return true;
  }
  const Index parents = mesh.Parents();
  for (Index p = 0; p < parents; ++p)
  {
    if (!Supports(mesh.Nodal->Type[p]))
    {
      return false;
    }
  }
  return EdgeShares(mesh) != (QuarterShare | SevenSixteenthsShare);
}

bool BernsteinForm::HasSigned(const MeshView& mesh)
{
  const Index parents = mesh.Nodal ? mesh.Parents() : 0;
  for (Index p = 0; p < parents; ++p)
  {
    if (Signed(mesh.Nodal->Type[p]))
    {
      return true;
    }
  }
  return false;
}

void BernsteinForm::Values(NodalType type, const double* xi, double* B)
{
  if (Signed(type))
  {
    TypeTable table;
    MakeSerendipityTable(type, table);
    double N[MaxNodalNodes];
    NodalValues(type, xi, N);
    for (int m = 0; m < table.Count; ++m)
    {
      B[m] = 0.0;
      for (int n = 0; n < table.Count; ++n)
      {
        B[m] += table.At[n][m] * N[n];
      }
    }
    return;
  }
  double nodes[3 * MaxNodalNodes];
  NodalReferenceNodes(type, nodes);
  const int count = NodalNodeCount(type);
  for (int m = 0; m < count; ++m)
  {
    int dimension = 0;
    B[m] = NodeBernstein(type, nodes + 3 * m, xi, &dimension);
  }
}

void BernsteinForm::Build(const MeshView& mesh)
{
  this->Built = true;
  this->AnySigned = HasSigned(mesh);
  const Index n = mesh.NumberOfPoints;
  // Each node's row from the first parent that has it (neighbours agree on
  // their common faces, so any would do).
  std::vector<Index> owner(static_cast<size_t>(n), -1);
  std::vector<unsigned char> local(static_cast<size_t>(n), 0);
  std::vector<TypeTable> tables(static_cast<size_t>(NodalType::Pyramid13) + 1);
  const Index parents = mesh.Nodal ? mesh.Parents() : 0;
  for (Index p = 0; p < parents; ++p)
  {
    const NodalType type = mesh.Nodal->Type[p];
    if (type == NodalType::None)
    {
      continue;
    }
    TypeTable& table = tables[static_cast<size_t>(type)];
    if (table.Count == 0)
    {
      MakeTable(type, table);
    }
    const long long* nodes = mesh.Nodal->Nodes + mesh.Nodal->Offsets[p];
    for (int k = 0; k < table.Count; ++k)
    {
      if (owner[static_cast<size_t>(nodes[k])] < 0)
      {
        owner[static_cast<size_t>(nodes[k])] = p;
        local[static_cast<size_t>(nodes[k])] = static_cast<unsigned char>(k);
      }
    }
  }
  this->C = CsrMatrix();
  this->C.Rows = this->C.Columns = n;
  this->C.RowStart.assign(static_cast<size_t>(n) + 1, 0);
  std::vector<int> dimension(static_cast<size_t>(n), 0);
  std::vector<std::pair<Column, double>> row;
  for (Index i = 0; i < n; ++i)
  {
    row.clear();
    const Index p = owner[static_cast<size_t>(i)];
    if (p < 0)
    {
      row.emplace_back(static_cast<Column>(i), 1.0); // a linear cell's point: P1
    }
    else
    {
      const TypeTable& table = tables[static_cast<size_t>(mesh.Nodal->Type[p])];
      const long long* nodes = mesh.Nodal->Nodes + mesh.Nodal->Offsets[p];
      const int k = local[static_cast<size_t>(i)];
      dimension[static_cast<size_t>(i)] = table.Dimension[k];
      for (int m = 0; m < table.Count; ++m)
      {
        if (table.At[k][m] != 0.0)
        {
          row.emplace_back(static_cast<Column>(nodes[m]), table.At[k][m]);
        }
      }
      std::sort(row.begin(), row.end());
    }
    for (const auto& entry : row)
    {
      this->C.ColumnIndex.push_back(entry.first);
      this->C.Values.push_back(entry.second);
    }
    this->C.RowStart[i + 1] = static_cast<Index>(this->C.ColumnIndex.size());
  }
  // FromNodes' order: corners, then edges, faces, bodies.
  this->Order.clear();
  this->Order.reserve(static_cast<size_t>(n));
  for (int d = 0; d <= 3; ++d)
  {
    for (Index i = 0; i < n; ++i)
    {
      if (dimension[static_cast<size_t>(i)] == d)
      {
        this->Order.push_back(i);
      }
    }
  }
}

void BernsteinForm::ToNodes(const double* b, int components, double* u) const
{
  double terms[MaxNodalNodes];
  for (Index i = 0; i < this->C.Rows; ++i)
  {
    const Index begin = this->C.RowStart[i];
    const int count = static_cast<int>(this->C.RowStart[i + 1] - begin);
    for (int k = 0; k < components; ++k)
    {
      for (int j = 0; j < count; ++j)
      {
        terms[j] = this->C.Values[begin + j] *
          b[static_cast<Index>(this->C.ColumnIndex[begin + j]) * components + k];
      }
      u[i * components + k] = SortedSum(terms, count);
    }
  }
}

void BernsteinForm::ToNodes(
  const double* b, int components, const std::vector<char>& usable, double* u) const
{
  double terms[MaxNodalNodes];
  double weights[MaxNodalNodes];
  for (Index i = 0; i < this->C.Rows; ++i)
  {
    const Index begin = this->C.RowStart[i];
    const int count = static_cast<int>(this->C.RowStart[i + 1] - begin);
    int used = 0;
    for (int j = 0; j < count; ++j)
    {
      used += usable[static_cast<size_t>(this->C.ColumnIndex[begin + j])] != 0;
    }
    double total = 1.0; // (every row's weights sum to 1 exactly: sixteenths)
    if (used < count)
    {
      int w = 0;
      for (int j = 0; j < count; ++j)
      {
        if (usable[static_cast<size_t>(this->C.ColumnIndex[begin + j])])
        {
          weights[w++] = this->C.Values[begin + j];
        }
      }
      total = SortedSum(weights, w);
    }
    for (int k = 0; k < components; ++k)
    {
      int t = 0;
      for (int j = 0; j < count; ++j)
      {
        const Index m = this->C.ColumnIndex[begin + j];
        if (usable[static_cast<size_t>(m)])
        {
          terms[t++] = this->C.Values[begin + j] * b[m * components + k];
        }
      }
      const double sum = SortedSum(terms, t);
      u[i * components + k] = used == 0 ? 0.0 : (used < count ? sum / total : sum);
    }
  }
}

void BernsteinForm::FromNodes(const double* u, int components, double* b) const
{
  double terms[MaxNodalNodes];
  for (const Index i : this->Order)
  {
    const Index begin = this->C.RowStart[i];
    const Index end = this->C.RowStart[i + 1];
    const double diagonal = this->C.Values[this->C.Find(i, i)];
    for (int k = 0; k < components; ++k)
    {
      int t = 0;
      for (Index p = begin; p < end; ++p)
      {
        const Index m = this->C.ColumnIndex[p];
        if (m != i)
        {
          terms[t++] = this->C.Values[p] * b[m * components + k];
        }
      }
      b[i * components + k] = (u[i * components + k] - SortedSum(terms, t)) / diagonal;
    }
  }
}

void BernsteinForm::Transpose(const double* x, int components, double* y) const
{
  std::fill(y, y + this->C.Rows * components, 0.0);
  for (Index i = 0; i < this->C.Rows; ++i)
  {
    for (Index p = this->C.RowStart[i]; p < this->C.RowStart[i + 1]; ++p)
    {
      const Index m = this->C.ColumnIndex[p];
      for (int k = 0; k < components; ++k)
      {
        y[m * components + k] += this->C.Values[p] * x[i * components + k];
      }
    }
  }
}

size_t BernsteinForm::MemoryBytes() const
{
  if (this->Empty())
  {
    return 0;
  }
  return this->C.RowStart.capacity() * sizeof(Index) +
    this->C.ColumnIndex.capacity() * sizeof(Column) + this->C.Values.capacity() * sizeof(double) +
    this->Order.capacity() * sizeof(Index);
}
} // namespace mp
