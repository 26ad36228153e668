// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkMeshProjectionMesh.h
 * @brief Private to vtkMeshProjectionFilter: a vtkUnstructuredGrid seen as
 *        the kernel's simplicial mesh, with VTK's neighbours and locator.
 *
 * Wrap() checks a grid (cell types, one dimension, finite coordinates, a
 * plane for triangles, fitted by mp::PlaneFrame) and views its arrays
 * without a copy when their types allow it (double points, 64-bit cell
 * array, no ghost cells). A 2D mesh is then seen in a plane frame
 * (UseFrame): the points are used in place for planes z = constant and
 * mapped into the frame otherwise. Ghost cells (DUPLICATECELL, HIDDENCELL)
 * are left out: the kernel then numbers only the other cells and ToVTK()
 * maps its ids back. Neighbours come from vtkStaticCellLinks through the
 * kernel's face matcher (mp::MatchFaces), seeds from vtkStaticCellLocator.
 *
 * Not a public class of the module: no export macro, not wrapped.
 */
#ifndef vtkMeshProjectionMesh_h
#define vtkMeshProjectionMesh_h

#include "Geometry/IntersectionPieces.h"
#include "Mesh/LargeArray.h"
#include "Mesh/MeshView.h"
#include "Mesh/PlaneFrame.h"
#include "Search/CandidateLocator.h"

#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <memory>
#include <mutex>
#include <string>
#include <vector>

class vtkIdList;
class vtkPolyData;
class vtkStaticCellLocator;
class vtkUnstructuredGrid;

namespace mpvtk
{
class SimplexMesh
{
public:
  /**
   * Checks `grid` and builds the kernel view. Returns an empty string, or
   * the reason the grid cannot be used (`role` names it: "Input", "Source").
   */
  std::string Wrap(vtkUnstructuredGrid* grid, const char* role);
  /// Face neighbours from vtkStaticCellLinks (call after Wrap).
  void BuildNeighbors();

  const mp::MeshView& View() const { return this->Kernel; }
  /// Sets the dimension of a mesh without cells (it takes the other mesh's).
  void SetDimension(int d) { this->Kernel.CellDimension = this->Kernel.SpaceDimension = d; }
  int Dimension() const { return this->Kernel.CellDimension; }
  /// For 2D meshes, the plane fitted to the mesh's own points by Wrap().
  const mp::PlaneFrame& OwnPlane() const { return this->Own; }
  /**
   * For 2D meshes: sees the points in `frame`'s 2D coordinates (in place
   * for planes z = constant, else mapped into a copy). Both meshes use the
   * same frame; this mesh's own plane may be parallel to it.
   */
  void UseFrame(const mp::PlaneFrame& frame);
  /// The frame the kernel sees the mesh in, moved onto the mesh's own plane.
  const mp::PlaneFrame& Frame() const { return this->Seen; }
  vtkIdType NonManifoldFaces() const { return this->NonManifold; }
  vtkIdType GhostCells() const { return this->Ghosts; }
  /// The VTK id of a kernel cell, and the kernel id of a VTK cell (-1 for a ghost).
  vtkIdType ToVTK(mp::Index c) const { return this->KernelToVTK.empty() ? c : this->KernelToVTK[c]; }
  mp::Index ToKernel(vtkIdType c) const { return this->VTKToKernel.empty() ? c : this->VTKToKernel[c]; }

private:
  vtkUnstructuredGrid* Grid = nullptr;
  mp::MeshView Kernel;
  std::vector<double> PointCopy;
  std::vector<mp::Index> ConnectivityCopy;
  const mp::Index* AllConnectivity = nullptr; ///< every cell of the grid, ghosts included
  std::vector<mp::Index> AllConnectivityCopy;
  mp::LargeVector<mp::NeighborId> Neighbors;
  std::vector<vtkIdType> KernelToVTK; ///< empty when the grid has no ghost cells
  std::vector<mp::Index> VTKToKernel; ///< -1 for ghost cells; empty likewise
  mp::PlaneFrame Own;
  mp::PlaneFrame Seen;
  vtkIdType NonManifold = 0;
  vtkIdType Ghosts = 0;
};

/**
 * The kernel's candidate search over a source mesh, answered by
 * vtkStaticCellLocator: one over the source's boundary cells (a grid of
 * those cells sharing the source's points), built at once, and one over the
 * whole source, built on the first question that needs it (see
 * CandidateLocator.h: on meshes of the same domain, never).
 */
class StaticLocator : public mp::CandidateLocator
{
public:
  /// `mesh` must have its neighbours (SimplexMesh::BuildNeighbors).
  StaticLocator(vtkUnstructuredGrid* grid, const SimplexMesh& mesh);
  ~StaticLocator() override;
  void FindCandidates(const double box[6], std::vector<mp::Index>& cells) override;
  void FindBoundaryCandidates(const double box[6], std::vector<mp::Index>& cells) override;
  /// Shares the VTK locators; queries (and the lazy build) are serialized by
  /// a shared mutex (they are rare: first seeds and cells at the source
  /// boundary), since VTK 9.2 does not document FindCellsWithinBounds as
  /// thread-safe.
  std::unique_ptr<mp::CandidateLocator> NewForThread() const override;

private:
  struct Shared;
  StaticLocator(std::shared_ptr<Shared> shared, const SimplexMesh& mesh);
  void Find(bool all, const double box[6], std::vector<mp::Index>& cells);

  const SimplexMesh& Mesh;
  std::shared_ptr<Shared> Locators;
  vtkNew<vtkIdList> Ids;
};

/// 2D: one polygon per intersecting pair in the target's plane, with
/// SourceCellId, TargetCellId (VTK ids) and Area.
vtkSmartPointer<vtkPolyData> MakeIntersectionPolygons(const mp::IntersectionPieces& pieces,
  const SimplexMesh& target, const SimplexMesh& source);
/// 3D: the tetrahedra decomposing each intersection polyhedron, with
/// SourceCellId, TargetCellId and Volume.
vtkSmartPointer<vtkUnstructuredGrid> MakeIntersectionPolyhedra(
  const mp::IntersectionPieces& pieces, const SimplexMesh& target, const SimplexMesh& source);
} // namespace mpvtk

#endif
