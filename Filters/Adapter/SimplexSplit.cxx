// SPDX-License-Identifier: BSD-3-Clause
// SimplexMesh::Split: a dataset's cells split into simplices on their own
// points (Geometry/CellSplit.h), for the datasets that are not already a
// grid of one simplex type.
#include "Adapter/SimplexMesh.h"
#include "Adapter/DataSetChecks.h"

#include "Adapter/Ghosts.h"
#include "Adapter/NodalTypes.h"
#include "Adapter/Threads.h"
#include "Geometry/CellSplit.h"
#include "Geometry/CurvedSplit.h"
#include "Geometry/NodalShapes.h"
#include "Geometry/NodalSplit.h"

#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkCellTypes.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace mpvtk
{
namespace
{
/// The shape of a standard 3D cell for the kernel's face tables.
bool StandardShape(int type, mp::CellShape& shape)
{
  switch (type)
  {
    case VTK_HEXAHEDRON:
      shape = mp::CellShape::Hexahedron;
      return true;
    case VTK_VOXEL:
      shape = mp::CellShape::Voxel;
      return true;
    case VTK_WEDGE:
      shape = mp::CellShape::Wedge;
      return true;
    case VTK_PYRAMID:
      shape = mp::CellShape::Pyramid;
      return true;
    case VTK_PENTAGONAL_PRISM:
      shape = mp::CellShape::PentagonalPrism;
      return true;
    case VTK_HEXAGONAL_PRISM:
      shape = mp::CellShape::HexagonalPrism;
      return true;
    default:
      return false;
  }
}

/// The dataset's points as doubles: its own array when it holds doubles
/// (the split grid then shares it), else a copy (explicit points for image
/// and rectilinear data).
vtkSmartPointer<vtkPoints> PointsAsDoubles(vtkDataSet* data)
{
  vtkPointSet* pointSet = vtkPointSet::SafeDownCast(data);
  if (pointSet && pointSet->GetPoints() && pointSet->GetPoints()->GetDataType() == VTK_DOUBLE)
  {
    return pointSet->GetPoints();
  }
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  const vtkIdType np = data->GetNumberOfPoints();
  points->SetNumberOfPoints(np);
  double* x = vtkDoubleArray::SafeDownCast(points->GetData())->GetPointer(0);
  if (pointSet && pointSet->GetPoints())
  {
    vtkPoints* from = pointSet->GetPoints();
    for (vtkIdType p = 0; p < np; ++p)
    {
      from->GetPoint(p, x + 3 * p);
    }
  }
  else
  {
    data->GetPoint(0, x); // structured data: computes its points, thread-safe after the first
    mpvtk::For(0, np, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType p = begin; p < end; ++p)
      {
        data->GetPoint(p, x + 3 * p);
      }
    });
  }
  return points;
}

/// The keys the splits order corners by: the GlobalIds point array when
/// there is a usable one, else none (empty: the point ids). With global
/// ids a cell is split alike in any piece of a distributed mesh and in
/// the whole mesh.
std::vector<mp::Index> SplitKeys(vtkDataSet* data)
{
  std::vector<mp::Index> keys;
  if (vtkDataArray* global = data->GetPointData()->GetGlobalIds())
  {
    const vtkIdType np = data->GetNumberOfPoints();
    if (global->GetNumberOfTuples() >= np && global->GetNumberOfComponents() == 1)
    {
      keys.resize(static_cast<size_t>(np));
      for (vtkIdType p = 0; p < np; ++p)
      {
        keys[p] = static_cast<mp::Index>(global->GetTuple1(p));
      }
    }
  }
  return keys;
}

/**
 * Splits one cell at a time into simplices appended to a list, on the
 * dataset's points `x` and with the corners ordered by `key` (null: point
 * ids). Scratch arrays are kept from cell to cell.
 */
class CellSplitter
{
public:
  CellSplitter(vtkDataSet* data, const double* x, const mp::Index* key)
    : Data(data)
    , Grid(vtkUnstructuredGrid::SafeDownCast(data))
    , X(x)
    , Key(key)
  {}

  /// Appends cell c's simplices (of type `type`) to `simplices`.
  mp::SplitStatus Split(vtkIdType c, int type, std::vector<mp::Index>& simplices)
  {
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    this->Data->GetCellPoints(c, npts, pts, this->Scratch);
    this->Ids.assign(pts, pts + npts); // ids and counts checked by CheckDataSet
    std::vector<mp::Index>& ids = this->Ids;
    switch (type)
    {
      case VTK_LINE:
      case VTK_TRIANGLE:
      case VTK_TETRA:
        simplices.insert(simplices.end(), ids.begin(), ids.end());
        return mp::SplitStatus::Split;
      case VTK_POLY_LINE:
        SplitPolyLine(ids, simplices);
        return mp::SplitStatus::Split;
      case VTK_PIXEL:
        std::swap(ids[2], ids[3]); // x, y order -> around the square
        VTK_FALLTHROUGH;
      case VTK_QUAD:
      case VTK_POLYGON:
        return mp::SplitPolygon(
                 this->X, ids.data(), static_cast<int>(ids.size()), simplices, this->Key)
          ? mp::SplitStatus::Split
          : mp::SplitStatus::NotStarShaped;
      case VTK_TRIANGLE_STRIP:
        SplitStrip(ids, simplices);
        return mp::SplitStatus::Split;
      case VTK_POLYHEDRON:
      {
        vtkIdType nfaces = 0;
        const vtkIdType* faces = nullptr;
        this->Grid->GetFaceStream(c, nfaces, faces);
        return mp::SplitPolyhedron(
          this->X, faces, static_cast<int>(nfaces), false, simplices, this->Key);
      }
      default:
        return this->SplitStandard(type, simplices);
    }
  }

  /**
   * Appends the simplices of second-order cell c (of VTK type `type`) on
   * its nodes (Geometry/NodalSplit.h). `nodal`: its kernel type, None
   * (nothing appended) when the type's order or node count is not
   * accepted; Nodes() then holds its nodes in the kernel type's order. A
   * cell naming a node twice is refused (`repeated` set), and so is one
   * with a node at a NaN or infinite coordinate (NonFiniteNode(): its
   * orientation tests would call it folded).
   */
  mp::SplitStatus SplitNodal(
    vtkIdType c, int type, std::vector<mp::Index>& simplices, mp::NodalType& nodal, bool& repeated)
  {
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    this->Data->GetCellPoints(c, npts, pts, this->Scratch);
    this->Count = npts;
    this->NonFinite = -1;
    repeated = false;
    nodal = this->Types.TypeOf(type, npts, this->Data, c);
    if (nodal == mp::NodalType::None)
    {
      return mp::SplitStatus::Split;
    }
    this->Ids.resize(static_cast<size_t>(npts));
    this->Types.Order(type, nodal, pts, this->Ids.data());
    this->Sorted.assign(this->Ids.begin(), this->Ids.end());
    std::sort(this->Sorted.begin(), this->Sorted.end());
    if (std::adjacent_find(this->Sorted.begin(), this->Sorted.end()) != this->Sorted.end())
    {
      repeated = true;
      return mp::SplitStatus::NotStarShaped;
    }
    for (const mp::Index id : this->Ids)
    {
      const double* p = this->X + 3 * id;
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      {
        this->NonFinite = id;
        return mp::SplitStatus::NotStarShaped;
      }
    }
    return mp::SplitNodalCell(nodal, this->X, this->Ids.data(), simplices, this->Key);
  }
  /// The node at a NaN or infinite coordinate that refused the last cell
  /// SplitNodal read, or -1.
  vtkIdType NonFiniteNode() const { return this->NonFinite; }
  /// The nodes of the last cell SplitNodal accepted, in its kernel type's order.
  const std::vector<mp::Index>& Nodes() const { return this->Ids; }
  /// The number of points of the last cell SplitNodal read.
  vtkIdType NodeCount() const { return this->Count; }

private:
  /// A polyline's segments, but those of a repeated point.
  static void SplitPolyLine(const std::vector<mp::Index>& ids, std::vector<mp::Index>& simplices)
  {
    for (size_t k = 0; k + 1 < ids.size(); ++k)
    {
      if (ids[k] != ids[k + 1])
      {
        simplices.insert(simplices.end(), { ids[k], ids[k + 1] });
      }
    }
  }

  /// A strip's triangles, but those with a repeated point.
  static void SplitStrip(const std::vector<mp::Index>& ids, std::vector<mp::Index>& simplices)
  {
    for (size_t k = 0; k + 2 < ids.size(); ++k)
    {
      if (ids[k] != ids[k + 1] && ids[k + 1] != ids[k + 2] && ids[k] != ids[k + 2])
      {
        // Every other triangle of a strip runs the other way round: as
        // VTK orients them, all alike (it matters on surfaces).
        const bool odd = k % 2 == 1;
        simplices.insert(
          simplices.end(), { ids[odd ? k + 1 : k], ids[odd ? k : k + 1], ids[k + 2] });
      }
    }
  }

  /// A standard 3D cell (hexahedron, wedge, ...) through its face table;
  /// a type without one gives nothing (cells of lower dimension are never
  /// asked).
  mp::SplitStatus SplitStandard(int type, std::vector<mp::Index>& simplices)
  {
    mp::CellShape shape;
    if (!StandardShape(type, shape))
    {
      return mp::SplitStatus::Split;
    }
    const int nfaces = mp::StandardCellFaces(shape, this->Ids.data(), this->Stream);
    return mp::SplitPolyhedron(this->X, this->Stream.data(), nfaces, true, simplices, this->Key);
  }

  vtkDataSet* Data;
  vtkUnstructuredGrid* Grid; ///< the face streams of polyhedra
  const double* X;
  const mp::Index* Key;
  vtkNew<vtkIdList> Scratch;
  std::vector<mp::Index> Ids;
  std::vector<mp::Index> Sorted;
  std::vector<mp::Index> Stream;
  NodalCellTypes Types;
  vtkIdType Count = 0;
  vtkIdType NonFinite = -1;
};

/// Whether a second-order cell's mid nodes lie off its straight edges
/// (NodalIsStraight, to the rounding of its coordinates).
bool IsCurved(mp::NodalType type, const double* x, const std::vector<mp::Index>& nodes)
{
  double X[3 * mp::MaxNodalNodes];
  for (size_t k = 0; k < nodes.size(); ++k)
  {
    std::copy(x + 3 * nodes[k], x + 3 * nodes[k] + 3, X + 3 * k);
  }
  return !mp::NodalIsStraight(type, X, 3, 1e-12);
}

/// What RefineCurved did with a cell.
enum class Refinement
{
  None,    ///< straight, or no finer level asked for
  Refined, ///< split on the finer lattice
  Folded   ///< curved, but its finer split folds: the one on its nodes stays
};

/// Replaces the simplices from `before` on (a curved cell's split on its
/// nodes) by its split on the finer lattice, when `curved` refines it.
Refinement RefineCurved(mp::CurvedSplitter& curved, mp::NodalType type, const double* x,
  const std::vector<mp::Index>& nodes, std::vector<mp::Index>& simplices, size_t before)
{
  if (curved.Level() < 2 || !mp::IsRefinedWhenCurved(type) || !IsCurved(type, x, nodes))
  {
    return Refinement::None;
  }
  std::vector<mp::Index> finer;
  if (!curved.Split(type, nodes.data(), finer))
  {
    return Refinement::Folded;
  }
  simplices.resize(before);
  simplices.insert(simplices.end(), finer.begin(), finer.end());
  return Refinement::Refined;
}

/// The number of curved cells of `data` of a type the finer split does not
/// take (IsRefinedWhenCurved): any of them keeps the whole mesh on its
/// nodes' split, whose faces they share conformingly. Ghost cells left out
/// (owned by another process, which counts them; or blanked) do not count.
vtkIdType CurvedUnrefinable(vtkDataSet* data, CellSplitter& splitter, const double* x)
{
  vtkIdType count = 0;
  std::vector<mp::Index> scratch;
  vtkUnsignedCharArray* ghosts = data->GetCellGhostArray();
  for (vtkIdType c = 0; c < data->GetNumberOfCells(); ++c)
  {
    const int type = data->GetCellType(c);
    if (!IsAcceptedNonlinear(type) || IsLeftOutGhost(ghosts, c))
    {
      continue;
    }
    mp::NodalType nodal = mp::NodalType::None;
    bool repeated = false;
    scratch.clear();
    if (splitter.SplitNodal(c, type, scratch, nodal, repeated) == mp::SplitStatus::Split &&
      nodal != mp::NodalType::None && !mp::IsRefinedWhenCurved(nodal) &&
      IsCurved(nodal, x, splitter.Nodes()))
    {
      ++count;
    }
  }
  return count;
}

/// Why the first refused cell (and `refused` - 1 more) cannot be split.
std::string Refusal(vtkDataSet* data, const char* role, int dimension, vtkIdType firstRefused,
  mp::SplitStatus firstStatus, vtkIdType refused)
{
  std::ostringstream why;
  why << role << " cell " << firstRefused << " (" << CellTypeName(data->GetCellType(firstRefused))
      << ") cannot be split into " << (dimension == 3 ? "tetrahedra" : "triangles")
      << " on its own corners: ";
  if (firstStatus == mp::SplitStatus::OpenFaces)
  {
    why << "its faces do not close a volume (an edge is not shared by exactly two faces)";
  }
  else if (dimension == 3)
  {
    why << "it is inverted, twisted or not convex enough (the cone from each of its corners "
           "over its faces folds over itself)";
  }
  else
  {
    why << "its outline crosses itself";
  }
  why << (refused > 1 ? "; " + std::to_string(refused - 1) + " more cells likewise" : std::string())
      << ". Check the mesh, or apply " << (dimension == 3 ? "Tetrahedralize" : "Triangulate")
      << " first.";
  return why.str();
}

/// Why second-order cell c (and `refused` - 1 more) cannot be used:
/// `nodal` None: its order or node count; `repeated`: a node named twice;
/// `nonFinite` (not -1): that node at a NaN or infinite coordinate; else
/// it folds.
std::string NodalRefusal(vtkDataSet* data, const char* role, vtkIdType c, mp::NodalType nodal,
  bool repeated, vtkIdType nonFinite, vtkIdType count, vtkIdType refused)
{
  std::ostringstream why;
  const int type = data->GetCellType(c);
  why << role << " cell " << c << " (" << CellTypeName(type) << ") ";
  if (nodal == mp::NodalType::None)
  {
    why << "has " << count << " nodes: only Lagrange cells of order 2 are accepted (3, 6, 9, 10, "
        << "27 or 18 nodes for curves, triangles, quadrilaterals, tetrahedra, hexahedra and "
        << "wedges, with HigherOrderDegrees 2 when given)";
  }
  else if (repeated)
  {
    why << "names one node twice: a second-order cell needs distinct corner, mid-edge and "
        << "mid-face nodes";
  }
  else if (nonFinite >= 0)
  {
    why << "has a node with a NaN or infinite coordinate (point " << nonFinite << ")";
  }
  else
  {
    why << "is folded: the simplices through its nodes do not all have one orientation (a "
        << "mid node lies beyond its cell or too far off its edge)";
  }
  why << (refused > 1 ? "; " + std::to_string(refused - 1) + " more cells likewise"
                      : std::string());
  if (nonFinite >= 0)
  {
    // (Tessellate would not mend the point.)
    why << ". Fix the points: the dataset is corrupt.";
    return why.str();
  }
  why << ". Check the mesh, or apply Tessellate first (it changes the mesh: it splits the cells "
      << "into linear ones).";
  return why.str();
}

/// The dataset's points then those a finer split of curved cells added.
vtkSmartPointer<vtkPoints> WithAddedPoints(vtkPoints* points, const std::vector<double>& added)
{
  auto all = vtkSmartPointer<vtkPoints>::New();
  all->SetDataTypeToDouble();
  const vtkIdType np = points->GetNumberOfPoints();
  all->SetNumberOfPoints(np + static_cast<vtkIdType>(added.size() / 3));
  double* to = vtkDoubleArray::SafeDownCast(all->GetData())->GetPointer(0);
  for (vtkIdType p = 0; p < np; ++p)
  {
    points->GetPoint(p, to + 3 * p);
  }
  std::copy(added.begin(), added.end(), to + 3 * np);
  return all;
}

/// The simplices (`corners` ids each) as a grid of their own on `points`.
vtkSmartPointer<vtkUnstructuredGrid> SimplexGridOf(
  vtkPoints* points, const std::vector<mp::Index>& simplices, int dimension)
{
  const int corners = dimension + 1;
  const vtkIdType n = static_cast<vtkIdType>(simplices.size() / corners);
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(n + 1);
  vtkIdType* o = offsets->GetPointer(0);
  for (vtkIdType i = 0; i <= n; ++i)
  {
    o[i] = corners * i;
  }
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(simplices.size()));
  std::copy(simplices.begin(), simplices.end(), connectivity->GetPointer(0));
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  grid->SetCells(SimplexType(dimension), cells);
  return grid;
}
} // namespace

vtkIdType SimplexMesh::CurvedUnrefinableCells(vtkDataSet* data)
{
  // (Before Wrap: a corrupt part counts nothing here and fails there, with
  // its message, agreed; its cells are not read.)
  if (!data || data->GetNumberOfCells() == 0 || !CheckDataSet(data, "").empty())
  {
    return 0;
  }
  const vtkSmartPointer<vtkPoints> points = PointsAsDoubles(data);
  const double* x = points->GetNumberOfPoints() > 0
    ? vtkDoubleArray::SafeDownCast(points->GetData())->GetPointer(0)
    : nullptr;
  const std::vector<mp::Index> keys = SplitKeys(data);
  CellSplitter splitter(data, x, keys.empty() ? nullptr : keys.data());
  return CurvedUnrefinable(data, splitter, x);
}

std::string SimplexMesh::Split(vtkDataSet* data, const char* role)
{
  const vtkIdType numberOfCells = data->GetNumberOfCells();
  const int dimension = this->Kernel.CellDimension;
  const vtkSmartPointer<vtkPoints> points = PointsAsDoubles(data);
  const double* x = points->GetNumberOfPoints() > 0
    ? vtkDoubleArray::SafeDownCast(points->GetData())->GetPointer(0)
    : nullptr;
  // Cells are split from their corner of lowest global id when there are
  // global ids, else of lowest point id (SplitKeys).
  const std::vector<mp::Index> keys = SplitKeys(data);
  CellSplitter splitter(data, x, keys.empty() ? nullptr : keys.data());
  this->Unrefined = this->CurvedLevel <= 1 ? 0
    : this->WholeUnrefinable >= 0          ? this->WholeUnrefinable
                                           : CurvedUnrefinable(data, splitter, x);
  mp::CurvedSplitter curved(x, static_cast<mp::Index>(points->GetNumberOfPoints()),
    this->Unrefined > 0 ? 1 : this->CurvedLevel, keys.empty() ? nullptr : keys.data());
  vtkUnsignedCharArray* ghosts = data->GetCellGhostArray();
  std::vector<mp::Index> simplices;
  simplices.reserve(static_cast<size_t>(numberOfCells) * (dimension == 3 ? 24 : 6));
  this->ParentIds.clear();
  this->ParentIds.reserve(static_cast<size_t>(numberOfCells) * (dimension == 3 ? 6 : 2));
  vtkIdType refused = 0;
  vtkIdType firstRefused = -1;
  mp::SplitStatus firstStatus = mp::SplitStatus::Split;
  // Why the first refused cell was, when it is second-order (NodalRefusal).
  bool firstIsNodal = false;
  mp::NodalType firstNodal = mp::NodalType::None;
  bool firstRepeated = false;
  vtkIdType firstNonFinite = -1;
  vtkIdType firstCount = 0;
  const int corners = dimension + 1;
  for (vtkIdType c = 0; c < numberOfCells; ++c)
  {
    const int type = data->GetCellType(c);
    if (type == VTK_EMPTY_CELL ||
      vtkCellTypes::GetDimension(static_cast<unsigned char>(type)) < dimension)
    {
      this->LowerDimensional += type != VTK_EMPTY_CELL;
      continue;
    }
    if (IsLeftOutGhost(ghosts, c))
    {
      ++this->Ghosts;
      continue;
    }
    const size_t before = simplices.size();
    mp::SplitStatus status = mp::SplitStatus::Split;
    if (IsAcceptedNonlinear(type))
    {
      mp::NodalType nodal = mp::NodalType::None;
      bool repeated = false;
      status = splitter.SplitNodal(c, type, simplices, nodal, repeated);
      if (nodal == mp::NodalType::None || status != mp::SplitStatus::Split)
      {
        if (refused++ == 0)
        {
          firstRefused = c;
          firstIsNodal = true;
          firstNodal = nodal;
          firstRepeated = repeated;
          firstNonFinite = splitter.NonFiniteNode();
          firstCount = splitter.NodeCount();
        }
        continue;
      }
      this->AddNodal(c, nodal, splitter.Nodes(), numberOfCells);
      const Refinement done = RefineCurved(curved, nodal, x, splitter.Nodes(), simplices, before);
      this->Refined += done == Refinement::Refined;
      this->Unrefined += done == Refinement::Folded;
    }
    else
    {
      status = splitter.Split(c, type, simplices);
    }
    if (status != mp::SplitStatus::Split)
    {
      firstRefused = refused++ == 0 ? c : firstRefused;
      firstStatus = refused == 1 ? status : firstStatus;
      continue;
    }
    const size_t added = (simplices.size() - before) / corners;
    this->Flat += added == 0;
    this->SplitCount += type != SimplexType(dimension);
    this->ParentIds.insert(this->ParentIds.end(), added, c);
  }
  if (refused > 0 && firstIsNodal)
  {
    return NodalRefusal(
      data, role, firstRefused, firstNodal, firstRepeated, firstNonFinite, firstCount, refused);
  }
  if (refused > 0)
  {
    return Refusal(data, role, dimension, firstRefused, firstStatus, refused);
  }
  this->FinishNodal(numberOfCells);
  this->Geometric = static_cast<vtkIdType>(curved.AddedCount());
  this->SplitGrid =
    SimplexGridOf(this->Geometric > 0 ? WithAddedPoints(points, curved.AddedPoints()) : points,
      simplices, dimension);
  return std::string();
}

void SimplexMesh::AddNodal(
  vtkIdType c, mp::NodalType nodal, const std::vector<mp::Index>& nodes, vtkIdType numberOfCells)
{
  if (!this->NodalStore)
  {
    this->NodalStore.reset(new NodalArrays);
    this->NodalStore->Types.assign(static_cast<size_t>(numberOfCells), mp::NodalType::None);
    this->NodalStore->Offsets.assign(static_cast<size_t>(numberOfCells) + 1, 0);
  }
  NodalArrays& store = *this->NodalStore;
  store.Types[c] = nodal;
  // Offsets hold each cell's count until FinishNodal sums them.
  store.Offsets[c + 1] = static_cast<long long>(nodes.size());
  store.Nodes.insert(store.Nodes.end(), nodes.begin(), nodes.end());
}

void SimplexMesh::FinishNodal(vtkIdType numberOfCells)
{
  if (!this->NodalStore)
  {
    return;
  }
  NodalArrays& store = *this->NodalStore;
  for (vtkIdType c = 0; c < numberOfCells; ++c)
  {
    store.Offsets[c + 1] += store.Offsets[c];
  }
  store.View.Type = store.Types.data();
  store.View.Offsets = store.Offsets.data();
  store.View.Nodes = store.Nodes.data();
  this->Kernel.Nodal = &store.View;
}

void SimplexMesh::UseNodalSpace()
{
  if (this->Kernel.Nodal)
  {
    return;
  }
  const mp::Index parents = this->Kernel.Parents();
  this->NodalStore.reset(new NodalArrays);
  this->NodalStore->Types.assign(static_cast<size_t>(parents), mp::NodalType::None);
  this->NodalStore->Offsets.assign(static_cast<size_t>(parents) + 1, 0);
  this->FinishNodal(parents);
}
} // namespace mpvtk
