// SPDX-License-Identifier: BSD-3-Clause
#include "Transfer/NodalSpace.h"

#include "Geometry/HiddenNodes.h"

#include <cmath>

namespace mp
{
namespace
{
/// The inverse of a d x d matrix (d = 1, 2, 3): of the edges from corner
/// 0 (column k - 1: corner k), or of their Gram matrix; false when singular.
bool InvertEdges(int d, const double (&e)[3][3], double (&inverse)[3][3])
{
  if (d == 1)
  {
    inverse[0][0] = 1.0 / e[0][0];
    return e[0][0] != 0.0;
  }
  if (d == 2)
  {
    const double det = e[0][0] * e[1][1] - e[0][1] * e[1][0];
    inverse[0][0] = e[1][1] / det;
    inverse[0][1] = -e[0][1] / det;
    inverse[1][0] = -e[1][0] / det;
    inverse[1][1] = e[0][0] / det;
    return det != 0.0;
  }
  double c[3][3]; // cofactors, transposed: the adjugate
  for (int r = 0; r < 3; ++r)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      c[k][r] = e[r1][k1] * e[r2][k2] - e[r1][k2] * e[r2][k1];
    }
  }
  const double det = e[0][0] * c[0][0] + e[0][1] * c[1][0] + e[0][2] * c[2][0];
  for (int r = 0; r < 3; ++r)
  {
    for (int k = 0; k < 3; ++k)
    {
      inverse[r][k] = c[r][k] / det;
    }
  }
  return det != 0.0;
}

/// Mid nodes within this much of the cell's size from where the corners'
/// map puts them: the cell is taken as straight (its map affine). Far
/// below any curvature a mesher writes, far above rounding.
constexpr double StraightTolerance = 1e-12;

/**
 * The nodes of a cell of `type` at the reference origin and one unit step
 * along each reference axis (frame[0], then one per axis): the simplices'
 * corners, a quadrilateral's 0, 1, 3, a hexahedron's 0, 1, 3, 4, a wedge's
 * 0, 1, 2, 3. Where the cell is the affine image of its reference cell,
 * these nodes give that map. Returns how many (0: the pyramid, whose map
 * is never affine).
 */
int AffineFrame(NodalType type, int frame[4])
{
  switch (type)
  {
    case NodalType::Quad8:
    case NodalType::Quad9:
      frame[0] = 0, frame[1] = 1, frame[2] = 3;
      return 3;
    case NodalType::Hexa20:
    case NodalType::Hexa27:
      frame[0] = 0, frame[1] = 1, frame[2] = 3, frame[3] = 4;
      return 4;
    case NodalType::Pyramid13:
      return 0;
    default: // simplices and wedges: their first corners
      for (int k = 0; k < 4; ++k)
      {
        frame[k] = k;
      }
      return NodalCellDimension(type) + 1;
  }
}

/// Whether every node of the cell (its coordinates `nodes`, 3 each) is
/// where the affine map of its frame (AffineFrame) puts it, within
/// StraightTolerance of the cell's size.
bool IsAffineCell(NodalType type, const double* nodes, int dimension, const int frame[4])
{
  double reference[3 * MaxNodalNodes];
  NodalReferenceNodes(type, reference);
  const double* x0 = nodes + 3 * frame[0];
  double size = 0.0;
  double worst = 0.0;
  for (int n = 0; n < NodalNodeCount(type); ++n)
  {
    for (int a = 0; a < dimension; ++a)
    {
      double mapped = x0[a];
      for (int r = 0; r < NodalCellDimension(type); ++r)
      {
        mapped += reference[3 * n + r] * (nodes[3 * frame[r + 1] + a] - x0[a]);
      }
      worst = std::max(worst, std::fabs(nodes[3 * n + a] - mapped));
      size = std::max(size, std::fabs(nodes[3 * n + a] - x0[a]));
    }
  }
  return worst <= StraightTolerance * size;
}
} // namespace

int UniformFunctionCount(const MeshView& mesh, SpaceType space)
{
  if (space == SpaceType::P0)
  {
    return 1;
  }
  const int corners = mesh.CornersPerCell();
  if (space == SpaceType::DP1 || !mesh.Nodal)
  {
    return corners;
  }
  const NodalCells& nodal = *mesh.Nodal;
  int count = -1;
  for (Index p = 0; p < mesh.Parents(); ++p)
  {
    const int n = nodal.Type[p] == NodalType::None
      ? corners
      : static_cast<int>(nodal.Offsets[p + 1] - nodal.Offsets[p]);
    if (count >= 0 && n != count)
    {
      return 0;
    }
    count = n;
  }
  return std::max(count, 0);
}

std::string CheckNodalCells(const MeshView& mesh, const char* name)
{
  if (!mesh.Nodal)
  {
    return std::string();
  }
  const NodalCells& nodal = *mesh.Nodal;
  const Index parents = mesh.Parents();
  auto bad = [&](Index p, const char* why) {
    return std::string(name) + ": second-order cell " + std::to_string(p) + " " + why;
  };
  // (An empty part of a distributed second-order mesh has no types.)
  if ((parents > 0 && !nodal.Type) || !nodal.Offsets || nodal.Offsets[0] != 0)
  {
    return std::string(name) + ": second-order cells without their types or offsets";
  }
  for (Index p = 0; p < parents; ++p)
  {
    const NodalType type = nodal.Type[p];
    const Index count = nodal.Offsets[p + 1] - nodal.Offsets[p];
    if (type == NodalType::None ? count != 0 : count != NodalNodeCount(type))
    {
      return bad(p, "has a wrong number of nodes");
    }
    if (type != NodalType::None && NodalCellDimension(type) != mesh.CellDimension)
    {
      return bad(p, "has another dimension than its simplices");
    }
    for (Index i = nodal.Offsets[p]; i < nodal.Offsets[p + 1]; ++i)
    {
      if (nodal.Nodes[i] < 0 || nodal.Nodes[i] >= mesh.NumberOfPoints)
      {
        return bad(p, "names a node that does not exist");
      }
    }
  }
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const Index p = mesh.ParentOf(c);
    if (nodal.Type[p] == NodalType::None)
    {
      continue;
    }
    const Index* first = nodal.Nodes + nodal.Offsets[p];
    const Index* last = nodal.Nodes + nodal.Offsets[p + 1];
    const CellCorners corners = mesh.Cell(c);
    for (int k = 0; k < mesh.CornersPerCell(); ++k)
    {
      // (A curved cell split finer also has geometric-only points.)
      if (mesh.HasFunction(corners[k]) && std::find(first, last, corners[k]) == last)
      {
        return bad(p, "has a simplex on a point that is not one of its nodes");
      }
    }
  }
  return std::string();
}

void NodalFunctions::Bind(const MeshView& mesh, SpaceType space, Index c)
{
  if (space == this->Space &&
    (c == this->Cell ||
      (this->Type != NodalType::None && space == SpaceType::P1 &&
        mesh.ParentOf(c) == this->Parent)))
  {
    if (c != this->Cell && !this->Affine)
    {
      this->BindSimplex(mesh, c); // (only the start of the inverse map moves)
    }
    this->Cell = c; // (a second-order parent's functions are the same on all its simplices)
    return;
  }
  this->Cell = c;
  this->Space = space;
  this->Dimension = mesh.SpaceDimension;
  this->Corners = mesh.CornersPerCell();
  this->Type = NodalType::None;
  this->Sibling = NodalType::None;
  this->Affine = true;
  if (space == SpaceType::P0)
  {
    this->Parent = mesh.ParentOf(c);
    this->Count = 1;
    this->Dofs[0] = mesh.ParentOf(c);
    this->Degree = 0;
    return;
  }
  const Index p = mesh.ParentOf(c);
  this->Parent = p;
  const NodalType type = space == SpaceType::P1 ? NodalTypeOf(mesh, p) : NodalType::None;
  const CellCorners corners = mesh.Cell(c);
  // The affine simplex: the cell itself, or a simplex parent's corners.
  Index simplex[4];
  if (type == NodalType::None)
  {
    this->Count = this->Corners;
    this->Degree = 1;
    for (int k = 0; k < this->Corners; ++k)
    {
      simplex[k] = corners[k];
      this->Dofs[k] = space == SpaceType::DP1 ? c * this->Corners + k : corners[k];
    }
  }
  else
  {
    this->Type = type;
    this->Degree = NodalDegree(type);
    const NodalCells& nodal = *mesh.Nodal;
    this->Count = static_cast<int>(nodal.Offsets[p + 1] - nodal.Offsets[p]);
    std::copy(nodal.Nodes + nodal.Offsets[p], nodal.Nodes + nodal.Offsets[p + 1], this->Dofs);
    for (int n = 0; n < this->Count; ++n)
    {
      std::copy(mesh.Point(this->Dofs[n]), mesh.Point(this->Dofs[n]) + 3, this->Nodes + 3 * n);
    }
    // An affine image of the reference cell (a straight simplex, a
    // parallelogram, a parallelepiped, a straight prism): its functions
    // are polynomials in x, reached through one affine inverse.
    int frame[4];
    const int framed = AffineFrame(type, frame);
    this->Affine =
      framed == this->Corners && IsAffineCell(type, this->Nodes, this->Dimension, frame);
    if (!this->Affine)
    {
      this->BindHiddenNodes();
    }
    if (this->Affine)
    {
      double reference[3 * MaxNodalFunctions];
      NodalReferenceNodes(type, reference);
      for (int k = 0; k < this->Corners; ++k)
      {
        simplex[k] = this->Dofs[frame[k]];
        std::copy(reference + 3 * frame[k], reference + 3 * frame[k] + 3, this->Reference[k]);
      }
    }
  }
  if (this->Affine && (this->AffineMap(mesh, simplex) || type == NodalType::None))
  {
    return;
  }
  // A non-affine parent (or an affine one of zero measure, whose frame has
  // no inverse: its simplices have no pieces): Newton's inverse per point.
  this->Affine = false;
  this->Map.Prepare(type, this->Nodes, this->Dimension);
  this->BindSimplex(mesh, c);
}

void NodalFunctions::BindSimplex(const MeshView& mesh, Index c)
{
  double reference[3 * MaxNodalFunctions];
  NodalReferenceNodes(this->Type, reference);
  const CellCorners corners = mesh.Cell(c);
  Index simplex[4];
  for (int k = 0; k < this->Corners; ++k)
  {
    simplex[k] = corners[k];
    const int n =
      static_cast<int>(std::find(this->Dofs, this->Dofs + this->Count, corners[k]) - this->Dofs);
    if (n < this->Count)
    {
      std::copy(reference + 3 * n, reference + 3 * n + 3, this->Reference[k]);
    }
    else
    {
      // A point a curved cell's finer split adds (CurvedSplit.h) is no node:
      // its reference point is found once per simplex bound (the centre's
      // image where even that fails), so that the points of the simplex
      // start near their own.
      const double* x = mesh.Point(corners[k]);
      const double point[3] = { x[0], x[1], this->Dimension == 3 ? x[2] : 0.0 };
      if (!this->Map.FindFromCentre(point, this->Reference[k]))
      {
        std::copy(this->Map.ReferenceCentre(), this->Map.ReferenceCentre() + 3, this->Reference[k]);
      }
    }
  }
  this->AffineMap(mesh, simplex);
}

bool NodalFunctions::AffineMap(const MeshView& mesh, const Index* simplex)
{
  const double* x0 = mesh.Point(simplex[0]);
  std::copy(x0, x0 + 3, this->Origin);
  const int d = this->Corners - 1;
  const int n = this->Dimension;
  double e[3][3] = {}; // column k - 1: corner k - corner 0
  for (int k = 1; k <= d; ++k)
  {
    for (int a = 0; a < n; ++a)
    {
      e[a][k - 1] = mesh.Point(simplex[k])[a] - x0[a];
    }
  }
  bool regular = true;
  if (d == n)
  {
    regular = InvertEdges(d, e, this->Inverse);
  }
  else
  {
    regular = this->ProjectionInverse(e);
  }
  if (!regular)
  {
    for (auto& row : this->Inverse)
    {
      std::fill(row, row + 3, 0.0); // (every point then has corner 0's coordinates)
    }
  }
  return regular;
}

bool NodalFunctions::ProjectionInverse(const double (&e)[3][3])
{
  const int d = this->Corners - 1;
  const int n = this->Dimension;
  // A facet or segment in a higher space: the least-squares inverse
  // (E^T E)^-1 E^T, which maps a point to the barycentric coordinates of
  // its orthogonal projection onto the simplex's plane or line.
  double g[3][3] = {};
  for (int r = 0; r < d; ++r)
  {
    for (int k = 0; k < d; ++k)
    {
      for (int a = 0; a < n; ++a)
      {
        g[r][k] += e[a][r] * e[a][k];
      }
    }
  }
  double gi[3][3];
  if (!InvertEdges(d, g, gi))
  {
    return false;
  }
  for (int r = 0; r < d; ++r)
  {
    for (int a = 0; a < n; ++a)
    {
      double v = 0.0;
      for (int k = 0; k < d; ++k)
      {
        v += gi[r][k] * e[a][k];
      }
      this->Inverse[r][a] = v;
    }
  }
  return true;
}

void NodalFunctions::Barycentric(const double* x, double* lambda) const
{
  const int d = this->Corners - 1;
  const int n = this->Dimension;
  double shift[3];
  for (int a = 0; a < n; ++a)
  {
    shift[a] = x[a] - this->Origin[a];
  }
  double sum = 0.0;
  for (int r = 0; r < d; ++r)
  {
    double v = 0.0;
    for (int a = 0; a < n; ++a)
    {
      v += this->Inverse[r][a] * shift[a];
    }
    lambda[r + 1] = v;
    sum += v;
  }
  lambda[0] = 1.0 - sum;
}

int NodalFunctions::Coordinates(const double* x, double* c) const
{
  if (this->Space == SpaceType::P0)
  {
    return 0;
  }
  if (this->Type == NodalType::None)
  {
    this->Barycentric(x, c);
    return this->Corners;
  }
  double lambda[4];
  this->Barycentric(x, lambda);
  for (int a = 0; a < 3; ++a)
  {
    c[a] = 0.0;
    for (int k = 0; k < this->Corners; ++k)
    {
      c[a] += lambda[k] * this->Reference[k][a];
    }
  }
  return 3;
}

void NodalFunctions::ValuesAt(const double* c, double* values) const
{
  if (this->Space == SpaceType::P0)
  {
    values[0] = 1.0;
  }
  else if (this->Type == NodalType::None)
  {
    std::copy(c, c + this->Corners, values);
  }
  else
  {
    NodalValues(this->Type, c, values);
  }
}

void NodalFunctions::Values(const double* x, double* values) const
{
  if (this->Affine)
  {
    double c[4];
    this->Coordinates(x, c);
    this->ValuesAt(c, values);
    return;
  }
  // Newton from x's image under the bound simplex's affine map, else from
  // the centre; where both fail (past a fold, a singular Jacobian) that
  // image is taken, a defined point of the cell, and counted.
  double start[3] = { 0.0, 0.0, 0.0 };
  this->Coordinates(x, start);
  double xi[3] = { 0.0, 0.0, 0.0 };
  const double point[3] = { x[0], x[1], this->Dimension == 3 ? x[2] : 0.0 };
  if (!this->Map.Find(point, start, xi) && !this->Map.FindFromCentre(point, xi))
  {
    ++this->Unconverged;
    std::copy(start, start + 3, xi);
  }
  if (this->Sibling != NodalType::None)
  {
    HiddenNodeFunctions(this->Type, this->Hidden, xi, values);
  }
  else
  {
    NodalValues(this->Type, xi, values);
  }
}

void NodalFunctions::BindHiddenNodes()
{
  this->Sibling = CompleteSibling(this->Type);
  if (this->Sibling == NodalType::None)
  {
    return;
  }
  HiddenNodeWeights(this->Type, this->Nodes, this->Dofs, this->Dimension, this->Hidden);
  this->Degree = NodalDegree(this->Sibling);
}
} // namespace mp
