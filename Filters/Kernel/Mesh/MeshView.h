// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MeshView.h
 * @brief Non-owning view of a simplicial mesh given as flat arrays.
 *
 * The kernel never owns mesh data: callers (the VTK filter, tests, a future
 * numpy binding) hand it pointers to their own arrays. The view keeps two
 * dimensions apart:
 *  - CellDimension, the dimension of the simplices: 1 (segments), 2
 *    (triangles) or 3 (tetrahedra), stored cell after cell in
 *    `Connectivity` with CellDimension + 1 corners each;
 *  - SpaceDimension, how many coordinates of a point the geometry uses:
 *    2 (x, y) or 3 (x, y, z). Points are always stored with three
 *    coordinates, as VTK does; a planar mesh in any plane is seen in 2D
 *    through a PlaneFrame (PlaneFrame.h): its points' (x, y) in place for
 *    planes z = constant, else mapped into (u, v, 0).
 * The geometry exists for triangles in the plane and tetrahedra in space
 * (CellDimension == SpaceDimension) and for triangles of surfaces in 3D
 * (CellDimension 2, SpaceDimension 3) and for segments of curves
 * (CellDimension 1, SpaceDimension 2 or 3).
 *
 * Cells that are not simplices (quads, hexahedra, polyhedra) are given as
 * the simplices they are split into, with `Parent` naming the original cell
 * of each simplex: the P0 space and the covered fractions then belong to the
 * original cells (NumberOfParents of them). Without Parent, every simplex is
 * its own parent.
 *
 * Face k of a cell is the face opposite its corner k. `Neighbors`, when set,
 * holds for every cell and every face the cell across that face, or -1.
 */
#ifndef MeshProjection_Kernel_MeshView_h
#define MeshProjection_Kernel_MeshView_h

#include <cstdint>

namespace mp
{
/// Cell and point ids: 64-bit, and the same type as VTK's vtkIdType and
/// vtkTypeInt64 (long long), so VTK's arrays can be viewed without a copy.
using Index = long long;
static_assert(sizeof(Index) == 8, "mp::Index must be a 64-bit integer");

/// Cell ids in the neighbour table: 32 bits (half the memory of the table,
/// which is as large as the connectivity), so meshes searched by the
/// advancing front have fewer than 2^31 cells.
using NeighborId = int;
static_assert(sizeof(NeighborId) == 4, "mp::NeighborId must be a 32-bit integer");

struct PointCells;
struct NodalCells;

/**
 * The corners of one cell, read from a 64-bit or a 32-bit connectivity
 * (MeshView::Connectivity, MeshView::Connectivity32), indexed like an array.
 */
class CellCorners
{
public:
  CellCorners(const Index* wide, const std::int32_t* narrow)
    : Wide(wide)
    , Narrow(narrow)
  {}
  Index operator[](Index k) const { return this->Narrow ? Index(this->Narrow[k]) : this->Wide[k]; }
  /// Where the corners are stored (to prefetch them).
  const void* Address() const
  {
    return this->Narrow ? static_cast<const void*>(this->Narrow)
                        : static_cast<const void*>(this->Wide);
  }

private:
  const Index* Wide;
  const std::int32_t* Narrow;
};

struct MeshView
{
  int CellDimension = 2;          ///< 1: segments, 2: triangles, 3: tetrahedra
  int SpaceDimension = 2;         ///< coordinates used: 2 (x, y) or 3 (x, y, z)
  const double* Points = nullptr; ///< 3 * AllPoints() coordinates
  Index NumberOfPoints = 0;       ///< the points that carry functions (P1), first
  /// Points after those that carry geometry only: the lattice points of
  /// curved second-order cells split finer than on their nodes
  /// (Geometry/CurvedSplit.h). They are corners of simplices of
  /// second-order parents only, whose functions are the parents' nodes, so
  /// no function lives on them.
  Index GeometricPoints = 0;
  const Index* Connectivity = nullptr; ///< (CellDimension + 1) * NumberOfCells point ids
  /// The same in 32 bits (half the memory: a renumbered copy of a mesh of
  /// fewer than 2^31 points); when set, it is read instead of Connectivity.
  const std::int32_t* Connectivity32 = nullptr;
  Index NumberOfCells = 0;
  /// The original cell of each simplex (null: each simplex is its own).
  const Index* Parent = nullptr;
  Index NumberOfParents = 0; ///< with Parent: how many original cells
  /// With Parent: every original cell is exactly one simplex (Parent is a
  /// permutation: the cells were only renumbered), so per-parent sums are
  /// per-cell values moved.
  bool OneCellPerParent = false;
  const NeighborId* Neighbors = nullptr; ///< (CellDimension + 1) * NumberOfCells cell ids or -1
  /// The cells around each point, when the neighbours' construction kept
  /// them (CellNeighbors.h): M_tt's pattern reads them instead of building
  /// them again, and empties them. Null: not kept (the filter does not keep
  /// them: M_tt comes after the search, which they would take room from).
  PointCells* Around = nullptr;
  /// Second-order cells split on their nodes: each parent's type and nodes
  /// (NodalCells.h); null when every cell is linear.
  const NodalCells* Nodal = nullptr;
  /**
   * Surfaces in 3D (CellDimension 2, SpaceDimension 3) and curves
   * (CellDimension 1), read from the target's view: a source facet meets a
   * target facet only within this distance of the target facet's plane
   * (line), relative to the target facet's longest edge
   * (Geometry/SurfaceIntersector.h, SegmentIntersector.h) ...
   */
  double SurfaceReach = 0.5;
  /// ... and only when the cosine of their normals' angle (for curves: of
  /// their directions', without sign) is at least this (45 degrees) ...
  double SurfaceMinCosine = 0.70710678118654752;
  /// ... the normals compared as they are (0: two facetizations of one
  /// surface), one of them reversed (1: two bodies' boundaries facing each
  /// other, as in contact or fluid-structure coupling), or either way (2).
  int SurfaceOrientation = 0;

  int CornersPerCell() const { return this->CellDimension + 1; }
  CellCorners Cell(Index c) const
  {
    const Index at = c * this->CornersPerCell();
    return this->Connectivity32 ? CellCorners(nullptr, this->Connectivity32 + at)
                                : CellCorners(this->Connectivity + at, nullptr);
  }
  /// Entry i of the connectivity (corner i % corners of cell i / corners).
  Index Corner(Index i) const
  {
    return this->Connectivity32 ? Index(this->Connectivity32[i]) : this->Connectivity[i];
  }
  /// Whether the mesh has its connectivity (in either width).
  bool HasConnectivity() const { return this->Connectivity || this->Connectivity32; }
  const double* Point(Index p) const { return this->Points + 3 * p; }
  /// Every point a simplex may name: NumberOfPoints + GeometricPoints.
  Index AllPoints() const { return this->NumberOfPoints + this->GeometricPoints; }
  /// Whether point p carries a function (not a geometric-only point).
  bool HasFunction(Index p) const { return p < this->NumberOfPoints; }
  Index Neighbor(Index c, int face) const
  {
    return this->Neighbors[c * this->CornersPerCell() + face];
  }
  /// The original cell of simplex c.
  Index ParentOf(Index c) const { return this->Parent ? this->Parent[c] : c; }
  /// How many original cells there are.
  Index Parents() const { return this->Parent ? this->NumberOfParents : this->NumberOfCells; }
  /// Simplices filling their space (triangles in the plane, tetrahedra).
  bool IsVolumeMesh() const { return this->CellDimension == this->SpaceDimension; }
  /// Segments of a curve, in the plane or in space.
  bool IsCurveMesh() const { return this->CellDimension == 1 && this->SpaceDimension >= 2; }
  /// Triangles of a surface in 3D.
  bool IsSurfaceMesh() const { return this->CellDimension == 2 && this->SpaceDimension == 3; }
};
} // namespace mp

#endif
