// SPDX-License-Identifier: BSD-3-Clause
#include "Adapter/SimplexMesh.h"

#include "Adapter/DataSetChecks.h"
#include "Adapter/Ghosts.h"
#include "Adapter/NodalTypes.h"
#include "Adapter/Threads.h"
#include "Mesh/CellNeighbors.h"
#include "Mesh/NumberingQuality.h"
#include "Mesh/SpatialOrder.h"

#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkCellTypes.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkPoints.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <type_traits>

namespace mpvtk
{
static_assert(std::is_same<vtkTypeInt64, mp::Index>::value,
  "the kernel's ids must match VTK's 64-bit connectivity for zero-copy views");

int SimplexType(int d)
{
  return d == 1 ? VTK_LINE : (d == 2 ? VTK_TRIANGLE : VTK_TETRA);
}

const char* CellTypeName(int type)
{
  // VTK 9.2's table swaps the names of the Lagrange and Bezier triangles
  // and quadrilaterals.
  switch (type)
  {
    case VTK_LAGRANGE_TRIANGLE:
      return "vtkLagrangeTriangle";
    case VTK_LAGRANGE_QUADRILATERAL:
      return "vtkLagrangeQuadrilateral";
    case VTK_BEZIER_TRIANGLE:
      return "vtkBezierTriangle";
    case VTK_BEZIER_QUADRILATERAL:
      return "vtkBezierQuadrilateral";
    default:
      break;
  }
  const char* name = vtkCellTypes::GetClassNameFromTypeId(type);
  return name ? name : "unknown cell type";
}

std::string SimplexMesh::Wrap(vtkDataSet* data, const char* role)
{
  {
    // Every id and offset within its array before any cell is read.
    const auto start = std::chrono::steady_clock::now();
    const std::string corrupt = CheckDataSet(data, role);
    this->CheckTime =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!corrupt.empty())
    {
      return corrupt;
    }
  }
  std::ostringstream why;
  const vtkIdType numberOfCells = data->GetNumberOfCells();
  vtkUnstructuredGrid* grid = vtkUnstructuredGrid::SafeDownCast(data);
  // The cell types present: from an unstructured grid's type array in one
  // pass, else cell by cell (constant time for structured data).
  bool present[256] = {};
  vtkUnsignedCharArray* typeArray = grid ? grid->GetCellTypesArray() : nullptr;
  if (typeArray)
  {
    const unsigned char* t = typeArray->GetPointer(0);
    for (vtkIdType c = 0; c < numberOfCells; ++c)
    {
      present[t[c]] = true;
    }
  }
  else
  {
    for (vtkIdType c = 0; c < numberOfCells; ++c)
    {
      present[data->GetCellType(c) & 255] = true;
    }
  }
  std::set<int> nonlinear;
  std::set<int> unsupported;
  int dimension = 0;
  this->NodalStore.reset();
  this->Kernel.Nodal = nullptr;
  this->Refined = 0;
  this->Unrefined = 0;
  this->Geometric = 0;
  for (int type = 1; type < 256; ++type)
  {
    if (!present[type])
    {
      continue;
    }
    if (!vtkCellTypes::IsLinear(static_cast<unsigned char>(type)) && !IsAcceptedNonlinear(type))
    {
      nonlinear.insert(type);
    }
    else if (type == VTK_CONVEX_POINT_SET)
    {
      unsupported.insert(type);
    }
    else
    {
      dimension = std::max(dimension, vtkCellTypes::GetDimension(static_cast<unsigned char>(type)));
    }
  }
  if (!nonlinear.empty())
  {
    why << role << " has nonlinear cells:";
    for (int type : nonlinear)
    {
      why << ' ' << CellTypeName(type) << " (" << type << ')';
    }
    why << ", which the projection does not take. " << AcceptedNonlinearCells()
        << " (split on their own nodes). For the others apply Tessellate first (it changes the "
           "mesh: it splits curved and higher-order cells into linear ones to a chosen accuracy).";
    return why.str();
  }
  if (!unsupported.empty())
  {
    why << role << " has convex point sets (" << VTK_CONVEX_POINT_SET << "): cells without "
        << "faces cannot be split conformingly; apply Tetrahedralize first.";
    return why.str();
  }
  if (numberOfCells > 0 && dimension < 1)
  {
    why << role << " has only vertices: point clouds cannot be projected (the projection "
        << "needs lines, 2D or 3D cells).";
    return why.str();
  }
  // Types other than the mesh's simplex, empty cells included: the grid is
  // viewed in place only when every cell is one simplex (regular offsets).
  int others = 0;
  for (int type = 0; type < 256; ++type)
  {
    others += present[type] && type != SimplexType(std::max(dimension, 1));
  }
  this->SetDimension(std::max(dimension, 1));
  if (grid && others == 0)
  {
    // Triangles only, or tetrahedra only: the grid as it is.
    return this->WrapSimplices(grid, role);
  }
  const std::string error = this->Split(data, role);
  if (!error.empty())
  {
    return error;
  }
  return this->WrapSimplices(this->SplitGrid, role, numberOfCells);
}

std::string SimplexMesh::WrapSimplices(
  vtkUnstructuredGrid* grid, const char* role, vtkIdType parents)
{
  this->SimplexGrid = grid;
  const vtkIdType numberOfCells = grid->GetNumberOfCells();
  this->ViewConnectivity(grid);
  std::vector<vtkIdType> kept; // the grid's cells that are not ghosts (when some are)
  const vtkIdType gridGhosts = this->LeaveOutGhosts(grid, kept);
  this->NameParents(parents, numberOfCells, gridGhosts, kept);
  this->ViewPoints(grid);
  // Everything below and after reads the mesh along space when it is renumbered.
  this->OrderInSpace();
  const std::string badPoint = this->CheckPoints(role);
  if (!badPoint.empty())
  {
    return badPoint;
  }
  this->SeeInPlaneOrSpace();
  return std::string();
}

void SimplexMesh::ViewConnectivity(vtkUnstructuredGrid* grid)
{
  // VTK's own array when it is 64-bit (the kernel's ids), else a copy.
  const vtkIdType numberOfCells = grid->GetNumberOfCells();
  vtkCellArray* cells = grid->GetCells();
  if (numberOfCells > 0 && cells->IsStorage64Bit())
  {
    this->AllConnectivity = cells->GetConnectivityArray64()->GetPointer(0);
  }
  else if (numberOfCells > 0)
  {
    vtkDataArray* connectivity = cells->GetConnectivityArray();
    this->AllConnectivityCopy.resize(static_cast<size_t>(connectivity->GetNumberOfValues()));
    for (vtkIdType i = 0; i < connectivity->GetNumberOfValues(); ++i)
    {
      this->AllConnectivityCopy[i] = static_cast<mp::Index>(connectivity->GetComponent(i, 0));
    }
    this->AllConnectivity = this->AllConnectivityCopy.data();
  }
}

vtkIdType SimplexMesh::LeaveOutGhosts(vtkUnstructuredGrid* grid, std::vector<vtkIdType>& kept)
{
  // Ghost cells (duplicated from another piece, or hidden) are left out.
  // (A split has none: Split() left out and counted the dataset's.)
  const vtkIdType numberOfCells = grid->GetNumberOfCells();
  const int corners = this->Kernel.CornersPerCell();
  vtkUnsignedCharArray* ghosts = grid->GetCellGhostArray();
  vtkIdType gridGhosts = 0;
  if (ghosts)
  {
    for (vtkIdType c = 0; c < numberOfCells; ++c)
    {
      gridGhosts += IsLeftOutGhost(ghosts, c);
    }
  }
  this->Ghosts += gridGhosts;
  this->Kernel.Connectivity32 = nullptr;
  if (gridGhosts == 0)
  {
    this->Kernel.Connectivity = this->AllConnectivity;
    this->Kernel.NumberOfCells = numberOfCells;
    return 0;
  }
  // A copy of the other cells: the kernel reads its cells contiguously.
  for (vtkIdType c = 0; c < numberOfCells; ++c)
  {
    if (!IsLeftOutGhost(ghosts, c))
    {
      kept.push_back(c);
      this->ConnectivityCopy.insert(this->ConnectivityCopy.end(),
        this->AllConnectivity + corners * c, this->AllConnectivity + corners * (c + 1));
    }
  }
  this->Kernel.Connectivity = this->ConnectivityCopy.data();
  this->Kernel.NumberOfCells = static_cast<mp::Index>(kept.size());
  return gridGhosts;
}

void SimplexMesh::NameParents(vtkIdType parents, vtkIdType numberOfCells, vtkIdType gridGhosts,
  const std::vector<vtkIdType>& kept)
{
  // P0 functions are numbered as the dataset's cells: the split's cells
  // name theirs (Split), a grid's simplices are its cells but ghost cells
  // get none. Never null then, so that the P0 space has one function per
  // cell of the dataset even when no cell gave a simplex (all ghosts, all flat).
  static const mp::Index noParent = 0;
  this->Kernel.Parent = nullptr;
  this->Kernel.NumberOfParents = 0;
  this->Kernel.OneCellPerParent = false;
  if (parents < 0 && gridGhosts > 0)
  {
    this->ParentIds.assign(kept.begin(), kept.end());
    parents = numberOfCells;
  }
  if (parents >= 0)
  {
    this->Kernel.Parent = this->ParentIds.empty() ? &noParent : this->ParentIds.data();
    this->Kernel.NumberOfParents = parents;
  }
}

void SimplexMesh::ViewPoints(vtkUnstructuredGrid* grid)
{
  // The points a curved cell's finer split added come last and carry no function.
  this->Kernel.NumberOfPoints = grid->GetNumberOfPoints() - this->Geometric;
  this->Kernel.GeometricPoints = this->Geometric;
  // VTK's own array when it holds doubles.
  vtkPoints* points = grid->GetPoints();
  vtkDoubleArray* doubles = points ? vtkDoubleArray::SafeDownCast(points->GetData()) : nullptr;
  if (doubles && doubles->GetNumberOfComponents() == 3)
  {
    this->Kernel.Points = doubles->GetPointer(0);
  }
  else if (points)
  {
    this->PointCopy.resize(3 * static_cast<size_t>(points->GetNumberOfPoints()));
    for (vtkIdType p = 0; p < points->GetNumberOfPoints(); ++p)
    {
      points->GetPoint(p, &this->PointCopy[3 * p]);
    }
    this->Kernel.Points = this->PointCopy.data();
  }
  this->OriginalPoints = this->Kernel.Points;
}

std::string SimplexMesh::CheckPoints(const char* role) const
{
  // The points the cells use: finite, and within the predicates' range.
  // The first use of a point that is not is reported. All points are
  // checked first, in storage order (a fraction of the uses, read
  // sequentially); the uses only when some point fails (it may be unused).
  const mp::MeshView& kernel = this->Kernel;
  auto ids = [&kernel](mp::Index u) { return kernel.Corner(u); };
  const mp::Index uses = kernel.CornersPerCell() * kernel.NumberOfCells;
  auto badPoint = [&kernel](mp::Index p) {
    const double* x = kernel.Point(p);
    bool bad = false;
    for (int d = 0; d < 3; ++d)
    {
      const double a = std::fabs(x[d]);
      bad |= !(a <= 1e100) || (a != 0.0 && a < 1e-100); // NaN fails a <= 1e100
    }
    return bad;
  };
  const mp::Index i = FirstWhere(kernel.AllPoints(), badPoint) == kernel.AllPoints()
    ? uses
    : FirstWhere(uses, [&](vtkIdType u) { return badPoint(ids(u)); });
  if (i >= uses)
  {
    return std::string();
  }
  std::ostringstream why;
  const double* x = kernel.Point(ids(i));
  if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
  {
    why << role << " has a point with a NaN or infinite coordinate (point "
        << this->DataSetPoint(ids(i)) << ").";
    return why.str();
  }
  for (int d = 0; d < 3; ++d)
  {
    const double a = std::fabs(x[d]);
    if (a != 0.0 && (a < 1e-100 || a > 1e100))
    {
      why << role << " has a coordinate of magnitude " << a << " (point "
          << this->DataSetPoint(ids(i))
          << "): coordinates must be 0 or between 1e-100 and 1e100 in magnitude, where "
          << "the exact geometric predicates can neither underflow nor overflow. Rescale "
          << "the mesh.";
      return why.str();
    }
  }
  return std::string();
}

void SimplexMesh::SeeInPlaneOrSpace()
{
  double deviation = 0.0;
  double size = 0.0;
  this->Kernel.SpaceDimension = this->Kernel.CellDimension;
  this->NotPlanar = false;
  if (this->Dimension() == 1)
  {
    // Curves are seen in space as they are, planar or not (SegmentIntersector.h).
    this->UseAsSurface();
    return;
  }
  if (this->Kernel.NumberOfCells > 0 && this->Dimension() == 2 &&
    !this->Own.Fit(this->Kernel, deviation, size, SMPTaskRunner()))
  {
    // Not in one plane: a surface in 3D (SurfaceIntersector.h).
    this->NotPlanar = true;
    this->UseAsSurface();
    return;
  }
  this->Seen = this->Own;
}

void SimplexMesh::OrderInSpace()
{
  const mp::Index n = this->Kernel.NumberOfCells;
  const mp::Index np = this->Kernel.NumberOfPoints;
  // Automatic: point ids or the ids of cells across a face that do not
  // follow space (NumberingQuality.h), measured only when it would decide.
  auto tidy = [&] { return mp::MeasureNumbering(this->Kernel, SMPTaskRunner()).Tidy(); };
  // (Geometric-only points would be mixed with the functions' points.)
  if (this->OrderingMode == NEVER || n == 0 || this->Geometric > 0 ||
    (this->OrderingMode == AUTOMATIC && (n < MinimumOrderedCells || tidy())))
  {
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  const mp::TaskRunner runner = SMPTaskRunner();
  mp::SpatialOrder order;
  mp::OrderAlongCurve(this->Kernel, order, runner);
  const int corners = this->Kernel.CornersPerCell();
  // The copy in the kernel's own arrays (on huge pages, without the offsets
  // and cell types a VTK grid would add: nothing reads it as one).
  mp::LargeBuffer<double> coordinates(3 * static_cast<size_t>(np)); // written whole by RenumberMesh
  // The parents overwrite the cell order (no array of their own). Point ids
  // in 32 bits below 2^31 points: half the memory of the copy's cells.
  const bool narrow = np < std::numeric_limits<std::int32_t>::max();
  mp::LargeBuffer<mp::Index> connectivity(narrow ? 0 : corners * static_cast<size_t>(n));
  mp::LargeBuffer<std::int32_t> connectivity32(narrow ? corners * static_cast<size_t>(n) : 0);
  if (narrow)
  {
    mp::RenumberMesh(
      this->Kernel, order, coordinates.data(), connectivity32.data(), order.Cells.data(), runner);
  }
  else
  {
    mp::RenumberMesh(
      this->Kernel, order, coordinates.data(), connectivity.data(), order.Cells.data(), runner);
  }
  // The kernel sees the copy; P0 functions and the pieces' ids still name
  // the dataset's cells (through Parent), P1 ones name kernel points
  // (DataSetPoint maps them back).
  if (!this->Kernel.Parent)
  {
    this->Kernel.NumberOfParents = n;
    this->Kernel.OneCellPerParent = true; // the renumbering is the only parent map
  }
  this->ParentIds.swap(order.Cells);
  this->Kernel.Parent = this->ParentIds.data();
  if (this->NodalStore)
  {
    // Second-order cells name their nodes by kernel point too.
    for (long long& node : this->NodalStore->Nodes)
    {
      node = order.NewPoint[node];
    }
  }
  this->OrderedConnectivity.swap(connectivity);
  this->OrderedConnectivity32.swap(connectivity32);
  this->Kernel.Connectivity = narrow ? nullptr : this->OrderedConnectivity.data();
  this->Kernel.Connectivity32 = narrow ? this->OrderedConnectivity32.data() : nullptr;
  this->OrderedPoints.swap(coordinates);
  this->Kernel.Points = this->OrderedPoints.data();
  this->OriginalPoints = this->Kernel.Points;
  this->PointOrder.swap(order.Points);
  // What the old numbering needed and nothing reads any more.
  mp::LargeVector<mp::Index>().swap(this->ConnectivityCopy);
  mp::LargeVector<mp::Index>().swap(this->AllConnectivityCopy);
  mp::LargeVector<double>().swap(this->PointCopy);
  this->AllConnectivity = nullptr;
  this->OrderTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void SimplexMesh::UseAsSurface()
{
  this->Kernel.SpaceDimension = 3;
  this->Kernel.Points = this->OriginalPoints;
  this->Seen = mp::PlaneFrame();
}

void SimplexMesh::UseFrame(const mp::PlaneFrame& frame)
{
  this->Kernel.SpaceDimension = 2;
  this->Seen = frame.Shifted(this->Own.Offset());
  if (frame.IsIdentity())
  {
    this->Kernel.Points = this->OriginalPoints;
  }
  else
  {
    std::vector<double> mapped;
    mp::MeshView original = this->Kernel;
    original.Points = this->OriginalPoints; // a mesh may be seen in several frames in turn
    frame.ToPlane(original, mapped);
    this->FramePoints.swap(mapped);
    this->Kernel.Points = this->FramePoints.data();
  }
}

void SimplexMesh::ReleaseGeometry()
{
  this->ReleaseNeighbors();
  this->OrderedPoints = mp::LargeBuffer<double>();
  this->OrderedConnectivity = mp::LargeBuffer<mp::Index>();
  this->OrderedConnectivity32 = mp::LargeBuffer<std::int32_t>();
  mp::LargeVector<double>().swap(this->PointCopy);
  std::vector<double>().swap(this->FramePoints);
  mp::LargeVector<mp::Index>().swap(this->ConnectivityCopy);
  mp::LargeVector<mp::Index>().swap(this->AllConnectivityCopy);
  this->AllConnectivity = nullptr;
  this->OriginalPoints = nullptr;
  this->Kernel.Points = nullptr;
  this->Kernel.Connectivity = nullptr;
  this->Kernel.Connectivity32 = nullptr;
}

void SimplexMesh::ReleaseOrder()
{
  mp::UninitializedLargeVector<mp::Index>().swap(this->PointOrder);
  if (this->Kernel.OneCellPerParent)
  {
    // Only a renumbering's parents (split cells keep theirs: Parents() counts them).
    mp::UninitializedLargeVector<mp::Index>().swap(this->ParentIds);
    this->Kernel.Parent = nullptr;
  }
}

void SimplexMesh::BuildNeighbors(bool keepPointCells)
{
  this->Around.reset();
  this->Kernel.Around = nullptr;
  const vtkIdType n = this->Kernel.NumberOfCells;
  const int corners = this->Kernel.CornersPerCell();
  if (n > std::numeric_limits<mp::NeighborId>::max())
  {
    return; // no neighbours: the kernel refuses the front for so many cells, and says so
  }
  // Every entry written by BuildFaceNeighbors (in the tasks), none before.
  this->Neighbors = mp::LargeBuffer<mp::NeighborId>(corners * static_cast<size_t>(n));
  this->Kernel.Neighbors = this->Neighbors.data();
  if (n == 0)
  {
    return;
  }
  // The kernel's own cells around each point (ghost cells are not the
  // kernel's: they are never neighbours).
  if (keepPointCells)
  {
    this->Around.reset(new mp::PointCells);
  }
  this->NonManifold = mp::BuildFaceNeighbors(
    this->Kernel, this->Neighbors.data(), SMPTaskRunner(), this->Around.get());
  if (this->Around && this->Around->Fit(this->Kernel))
  {
    this->Kernel.Around = this->Around.get();
  }
  else
  {
    this->Around.reset();
  }
}
} // namespace mpvtk
