// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SimplexMesh.h
 * @brief Any vtkDataSet seen as the kernel's simplicial mesh (mp::MeshView),
 *        with its face neighbours; the VTK side of every projection.
 *
 * Wrap() takes a dataset of any type (unstructured grid, polydata, image
 * data, rectilinear or structured grid). An unstructured grid of only
 * linear triangles or only tetrahedra is viewed as it is, without a copy
 * when its arrays' types allow it (double points, 64-bit cell array). Any
 * other dataset is split into simplices on its own points by the kernel's
 * vertex-id rule (Geometry/CellSplit.h) into a grid of triangles or
 * tetrahedra that shares the dataset's vtkPoints (image and rectilinear
 * data get explicit points); each simplex names its original cell
 * (MeshView::Parent), so cell data and covered fractions belong to the
 * original cells. The mesh's dimension is that of its highest-dimensional
 * cells; cells of lower dimension (vertices, lines, boundary faces) are
 * left out and counted. Second-order cells (Adapter/NodalTypes.h: quadratic
 * cells and Lagrange cells of order 2) are split on their own nodes
 * (Geometry/NodalSplit.h) and remembered whole, with their nodes in kernel
 * point ids (View().Nodal, Mesh/NodalCells.h; null when there are none);
 * other nonlinear cells are refused by name, naming Tessellate.
 *
 * A 2D mesh is then seen in a plane frame (UseFrame): the points are used
 * in place for planes z = constant and mapped into the frame otherwise.
 * Ghost cells (Adapter/Ghosts.h: DUPLICATECELL, HIDDENCELL) are left out.
 * The kernel's P0 functions are numbered as the dataset's cells (ghost and
 * lower-dimensional cells have none of the mesh in them, so they are never
 * covered). Neighbours come from the kernel's face matcher
 * (mp::BuildFaceNeighbors) over the kernel's cells.
 *
 * Contract: the dataset must outlive the mesh and stay unchanged while the
 * kernel reads it (the view may be its own arrays). Wrap() reads nothing
 * before CheckDataSet (Adapter/DataSetChecks.h) has passed it.
 *
 * Not a public class of the module: no export macro, not wrapped.
 */
#ifndef MeshProjection_Adapter_SimplexMesh_h
#define MeshProjection_Adapter_SimplexMesh_h

#include "Mesh/CellNeighbors.h"
#include "Mesh/LargeArray.h"
#include "Mesh/MeshView.h"
#include "Mesh/NodalCells.h"
#include "Mesh/PlaneFrame.h"

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkDataSet;
class vtkUnstructuredGrid;

namespace mpvtk
{
/// The VTK type of the simplex of a mesh of dimension d: line, triangle or tetrahedron.
int SimplexType(int d);

/// VTK's name of a cell type, for messages.
const char* CellTypeName(int type);

/// A dataset seen as the kernel's simplicial mesh (see the file's comment).
class SimplexMesh
{
public:
  /**
   * Checks `data` and builds the kernel view (splitting cells that are not
   * simplices). Returns an empty string, or the reason the dataset cannot
   * be used (`role` names it: "Input", "Source").
   */
  std::string Wrap(vtkDataSet* data, const char* role);
  /**
   * Whether Wrap() renumbers the kernel's simplices and points along space
   * (SpatialOrder.h), in a copy: AUTOMATIC when the dataset's numbering is
   * far from following space (mp::NumberingQuality not Tidy(): the ids of a
   * cell's points or of the cells across its faces far apart, for at least
   * MinimumOrderedCells simplices), ALWAYS or NEVER.
   */
  enum Ordering
  {
    AUTOMATIC = 0,
    ALWAYS = 1,
    NEVER = 2
  };
  void SetOrdering(int ordering) { this->OrderingMode = ordering; }
  /**
   * The level L at which Wrap() splits curved second-order cells (mid nodes
   * off their straight edges): on the lattice of order 2L through their
   * isoparametric map (Geometry/CurvedSplit.h), adding the lattice points
   * that are not nodes as geometric-only points (View().GeometricPoints,
   * after the dataset's points: no function lives on them). 1: on their
   * nodes, as straight cells always are. A mesh with such points is not
   * renumbered (SetOrdering).
   */
  void SetCurvedLevel(int level) { this->CurvedLevel = level < 1 ? 1 : level; }
  int GetCurvedLevel() const { return this->CurvedLevel; }
  /// Curved cells Wrap() split on the finer lattice.
  vtkIdType RefinedCells() const { return this->Refined; }
  /**
   * Curved cells the last Wrap() left on their nodes' split although the
   * level asked for more: those of a type the finer split does not take
   * (hexahedra, wedges, pyramids: then no cell of the mesh is split finer,
   * so that their faces shared with refined cells stay conforming) and
   * those whose finer split folds (kept on their nodes: next to a refined
   * neighbour the covered part has slivers along their shared face). The
   * former are the whole mesh's when SetWholeCurvedUnrefinable() gave
   * them; the latter are always those of the cells this Wrap() split.
   */
  vtkIdType UnrefinedCurvedCells() const { return this->Unrefined; }
  /**
   * The curved second-order cells of `data` of a type the finer split does
   * not take (hexahedra, wedges, pyramids): one of them keeps a whole mesh
   * on its nodes' split. Ghost cells left out (IsLeftOutGhost) do not
   * count: summed over the processes' parts, each cell counts once. Null: 0.
   */
  static vtkIdType CurvedUnrefinableCells(vtkDataSet* data);
  /**
   * Those of the whole mesh, when the next Wrap() gets a part of it (on
   * several processes: the sum over their parts), so that the part is split
   * as the whole mesh alone (and UnrefinedCurvedCells() counts the whole's).
   * Default -1: the part is the whole mesh, Wrap() counts them.
   */
  void SetWholeCurvedUnrefinable(vtkIdType count) { this->WholeUnrefinable = count; }
  static constexpr vtkIdType MinimumOrderedCells = 4096;
  /// Whether the kernel's numbering is a renumbered copy (see SetOrdering).
  bool Ordered() const { return !this->PointOrder.empty(); }
  /// The dataset's point of kernel point p.
  vtkIdType DataSetPoint(mp::Index p) const
  {
    return this->PointOrder.empty() ? p : this->PointOrder[p];
  }
  /// Kernel point -> dataset point, or null when they are the same.
  const mp::Index* PointOrderData() const
  {
    return this->PointOrder.empty() ? nullptr : this->PointOrder.data();
  }
  /// Seconds Wrap() spent renumbering (0 when it did not).
  double OrderSeconds() const { return this->OrderTime; }
  /// The simplices, before any renumbering: the dataset itself, or its split.
  vtkUnstructuredGrid* Grid() const { return this->SimplexGrid; }
  /// The kernel's points in space (before any plane frame), 3 per point.
  const double* SpacePoints() const { return this->OriginalPoints; }
  /// Cells left out for being of lower dimension than the mesh (vertices,
  /// lines, faces of a volume mesh).
  vtkIdType LowerDimensionalCells() const { return this->LowerDimensional; }
  /// Cells whose split has no area or volume (flat cells).
  vtkIdType FlatCells() const { return this->Flat; }
  /// Cells that were split (not simplices already).
  vtkIdType SplitCells() const { return this->SplitCount; }
  /// Seconds Wrap() spent in CheckDataSet.
  double CheckSeconds() const { return this->CheckTime; }
  /// Face neighbours, matched by the kernel in the filter's threads (call
  /// after Wrap). `keepPointCells`: the cells around each point, which the
  /// matching builds, stay (View().Around) for the target mass matrix's
  /// pattern, until ReleaseNeighbors.
  /// Point data in the second-order cells' own space (View().Nodal, every
  /// parent linear) even where this part of the mesh has none: another
  /// process's part has some, and every process assembles and solves alike.
  void UseNodalSpace();
  void BuildNeighbors(bool keepPointCells = false);
  /// Gives the neighbours' memory back once no search will need them (and
  /// the cells around the points).
  void ReleaseNeighbors()
  {
    this->Neighbors = mp::LargeBuffer<mp::NeighborId>();
    this->Kernel.Neighbors = nullptr;
    this->Around.reset();
    this->Kernel.Around = nullptr;
  }

  /// Whether the kernel's points or cells are copies of the mesh's own (a
  /// renumbering, points of another type, cells without ghosts or of
  /// another width, points in a plane frame): what ReleaseGeometry gives back.
  bool OwnsGeometry() const
  {
    return !this->OrderedPoints.empty() || !this->OrderedConnectivity.empty() ||
      !this->OrderedConnectivity32.empty() || !this->PointCopy.empty() ||
      !this->ConnectivityCopy.empty() || !this->AllConnectivityCopy.empty() ||
      !this->FramePoints.empty();
  }
  /**
   * Gives back the kernel's points, cells and neighbours (copies, or the
   * view of the dataset's) once nothing reads them any more: the view
   * keeps its counts and parents, DataSetPoint its map, but no points or
   * cells (null).
   */
  void ReleaseGeometry();
  /**
   * After ReleaseGeometry, when nothing will map this mesh's points or
   * cells back any more (no operator kept for GetMatrix): gives back a
   * renumbering's maps too. DataSetPoint and ParentOf are then no longer
   * valid; the counts stay.
   */
  void ReleaseOrder();

  const mp::MeshView& View() const { return this->Kernel; }
  /// Sets the dimension of a mesh without cells (it takes the other mesh's).
  void SetDimension(int d) { this->Kernel.CellDimension = this->Kernel.SpaceDimension = d; }
  int Dimension() const { return this->Kernel.CellDimension; }
  /// For 2D meshes in one plane, the plane fitted to the mesh's own points by Wrap().
  const mp::PlaneFrame& OwnPlane() const { return this->Own; }
  /**
   * For 2D meshes: sees the points in `frame`'s 2D coordinates (in place
   * for planes z = constant, else mapped into a copy). Both meshes use the
   * same frame; this mesh's own plane may be parallel to it.
   */
  void UseFrame(const mp::PlaneFrame& frame);
  /**
   * For 2D meshes: sees the points as they are, in 3D, as a surface
   * (mp::SurfaceIntersector). Wrap() does so for a mesh that is not in one
   * plane, and for every curve (1D); a planar mesh matched with such a
   * surface is seen so too.
   */
  void UseAsSurface();
  /**
   * For curves in the plane of a 2D Source (a trace): sees the points in
   * `frame`'s 2D coordinates, as UseFrame, the frame being this curve's own plane.
   */
  void UseFrameAsOwn(const mp::PlaneFrame& frame)
  {
    this->Own = frame;
    this->UseFrame(frame);
  }
  /// Whether Wrap() found a 2D mesh that is not in one plane (a surface in 3D).
  bool Surface() const { return this->NotPlanar; }
  /// Surfaces: the reach and the cosine of the largest normals' angle (MeshView).
  void SetSurfaceContact(double reach, double minCosine, int orientation)
  {
    this->Kernel.SurfaceReach = reach;
    this->Kernel.SurfaceMinCosine = minCosine;
    this->Kernel.SurfaceOrientation = orientation;
  }
  /// The frame the kernel sees the mesh in, moved onto the mesh's own plane.
  const mp::PlaneFrame& Frame() const { return this->Seen; }
  vtkIdType NonManifoldFaces() const { return this->NonManifold; }
  /// Ghost cells left out (the dataset's; View().ParentOf(c) is the
  /// dataset's cell of kernel simplex c).
  vtkIdType GhostCells() const { return this->Ghosts; }

private:
  /// Wrap's last step: the kernel's view of a grid of simplices only.
  /// `parents`: the dataset's cells when `grid` is its split (ParentIds set), else -1.
  std::string WrapSimplices(vtkUnstructuredGrid* grid, const char* role, vtkIdType parents = -1);
  /// Splits every cell of the mesh's dimension into simplices (SplitGrid),
  /// counting the cells left out; an error names the first cell that
  /// cannot be split (SimplexSplit.cxx).
  std::string Split(vtkDataSet* data, const char* role);
  /// Split's record of second-order cell c (of `numberOfCells`): its type
  /// and its nodes (dataset point ids, in the type's order) ...
  void AddNodal(
    vtkIdType c, mp::NodalType nodal, const std::vector<mp::Index>& nodes, vtkIdType numberOfCells);
  /// ... and the view of them all (View().Nodal), once every cell is split.
  void FinishNodal(vtkIdType numberOfCells);

  // WrapSimplices' steps, in their order.
  /// AllConnectivity: the grid's cells, ghosts included, as mp::Index.
  void ViewConnectivity(vtkUnstructuredGrid* grid);
  /// The kernel's cells: the grid's without its ghosts (counted, and
  /// returned; `kept` then lists the others), else all of them.
  vtkIdType LeaveOutGhosts(vtkUnstructuredGrid* grid, std::vector<vtkIdType>& kept);
  /// The kernel's parents: see WrapSimplices' `parents`.
  void NameParents(vtkIdType parents, vtkIdType numberOfCells, vtkIdType gridGhosts,
    const std::vector<vtkIdType>& kept);
  /// The kernel's points: the grid's own when they are doubles, else a copy.
  void ViewPoints(vtkUnstructuredGrid* grid);
  /// Renumbers the mesh along space (see SetOrdering), when it should.
  void OrderInSpace();
  /// The first point the cells use that is not finite or out of the
  /// predicates' range, as an error naming `role`, or an empty string.
  std::string CheckPoints(const char* role) const;
  /// How the kernel sees the mesh: curves and surfaces in space, a planar
  /// mesh in its own plane (Own, Seen).
  void SeeInPlaneOrSpace();

  vtkUnstructuredGrid* SimplexGrid = nullptr;
  vtkSmartPointer<vtkUnstructuredGrid> SplitGrid;    ///< when the dataset was split
  mp::UninitializedLargeVector<mp::Index> ParentIds; ///< the dataset's cell of each kernel simplex
  const double* OriginalPoints = nullptr;            ///< the points before any plane frame
  vtkIdType LowerDimensional = 0;
  vtkIdType Flat = 0;
  vtkIdType SplitCount = 0;
  int CurvedLevel = 1;
  vtkIdType WholeUnrefinable = -1; ///< SetWholeCurvedUnrefinable
  vtkIdType Refined = 0;
  vtkIdType Unrefined = 0; ///< UnrefinedCurvedCells
  vtkIdType Geometric = 0; ///< points the split added after the dataset's (geometric only)
  double CheckTime = 0;
  double OrderTime = 0;
  int OrderingMode = AUTOMATIC;
  mp::UninitializedLargeVector<mp::Index>
    PointOrder;                                   ///< kernel point -> dataset point (empty: same)
  mp::LargeBuffer<double> OrderedPoints;          ///< the renumbered points, when Ordered()
  mp::LargeBuffer<mp::Index> OrderedConnectivity; ///< and simplices
  mp::LargeBuffer<std::int32_t> OrderedConnectivity32; ///< or these, below 2^31 points
  mp::MeshView Kernel;
  mp::LargeVector<double> PointCopy;
  std::vector<double> FramePoints; ///< the points in a plane frame other than z = constant
  mp::LargeVector<mp::Index> ConnectivityCopy;
  const mp::Index* AllConnectivity = nullptr; ///< every cell of the grid, ghosts included
  mp::LargeVector<mp::Index> AllConnectivityCopy;
  mp::LargeBuffer<mp::NeighborId> Neighbors;
  std::unique_ptr<mp::PointCells> Around; ///< (on the heap: the view points to it)
  /// Second-order cells' types and nodes (kernel point ids once Wrap is done).
  struct NodalArrays
  {
    std::vector<mp::NodalType> Types; ///< per dataset cell
    std::vector<long long> Offsets;   ///< dataset cells + 1
    std::vector<long long> Nodes;
    mp::NodalCells View;
  };
  std::unique_ptr<NodalArrays> NodalStore; ///< (on the heap: the view points to it); null without

  mp::PlaneFrame Own;
  mp::PlaneFrame Seen;
  vtkIdType NonManifold = 0;
  vtkIdType Ghosts = 0;
  bool NotPlanar = false;
};
} // namespace mpvtk

#endif
