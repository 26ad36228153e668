// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMeshProjectionFilter.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkCellTypes.h"
#include "vtkCharArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStaticCellLinks.h"
#include "vtkStaticCellLocator.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include "CandidateLocator.h"
#include "MortarProjector.h"

#include <atomic>
#include <algorithm>
#include <chrono>
#include <functional>
#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkMeshProjectionFilter);

namespace
{
static_assert(std::is_same<vtkTypeInt64, mp::Index>::value,
  "the kernel's ids must match VTK's 64-bit connectivity for zero-copy views");

/// A simplicial mesh as the kernel sees it: views of VTK's arrays where their
/// types allow it, converted copies otherwise.
struct KernelMesh
{
  mp::MeshView View;
  std::vector<double> PointCopy;
  std::vector<mp::Index> ConnectivityCopy;
  std::vector<mp::Index> Neighbors;
  double PlaneZ = 0;
  vtkIdType NonManifoldFaces = 0;
};

/// Checks that `grid` is a mesh of linear triangles in a plane z = constant
/// (2D) or of linear tetrahedra (3D) with finite coordinates, and wraps it.
/// Returns an empty string or the reason it cannot be used.
std::string WrapSimplexMesh(vtkUnstructuredGrid* grid, const char* role, KernelMesh& mesh)
{
  std::ostringstream why;
  const vtkIdType numberOfCells = grid->GetNumberOfCells();
  std::set<int> types;
  for (vtkIdType c = 0; c < numberOfCells; ++c)
  {
    types.insert(grid->GetCellType(c));
  }
  std::set<int> unsupported = types;
  unsupported.erase(VTK_TRIANGLE);
  unsupported.erase(VTK_TETRA);
  if (!unsupported.empty())
  {
    why << role << " has cells of types the filter does not support:";
    for (int type : unsupported)
    {
      const char* name = vtkCellTypes::GetClassNameFromTypeId(type);
      why << ' ' << (name ? name : "unknown") << " (" << type << ')';
    }
    why << ". Only linear triangles (2D) and tetrahedra (3D) are supported; apply Triangulate "
           "(2D) or Tetrahedralize (3D) first.";
    return why.str();
  }
  if (types.size() > 1)
  {
    why << role << " mixes triangles and tetrahedra: give 2D and 3D meshes separately.";
    return why.str();
  }
  mesh.View.Dimension = types.count(VTK_TETRA) ? 3 : 2;
  const int corners = mesh.View.Dimension + 1;

  vtkCellArray* cells = grid->GetCells();
  mesh.View.NumberOfCells = numberOfCells;
  mesh.View.NumberOfPoints = grid->GetNumberOfPoints();
  if (numberOfCells > 0 && cells->IsStorage64Bit())
  {
    mesh.View.Connectivity = cells->GetConnectivityArray64()->GetPointer(0);
  }
  else if (numberOfCells > 0)
  {
    vtkDataArray* connectivity = cells->GetConnectivityArray();
    mesh.ConnectivityCopy.resize(static_cast<size_t>(connectivity->GetNumberOfValues()));
    for (vtkIdType i = 0; i < connectivity->GetNumberOfValues(); ++i)
    {
      mesh.ConnectivityCopy[i] = static_cast<mp::Index>(connectivity->GetComponent(i, 0));
    }
    mesh.View.Connectivity = mesh.ConnectivityCopy.data();
  }

  vtkPoints* points = grid->GetPoints();
  vtkDoubleArray* doubles =
    points ? vtkDoubleArray::SafeDownCast(points->GetData()) : nullptr;
  if (doubles && doubles->GetNumberOfComponents() == 3)
  {
    mesh.View.Points = doubles->GetPointer(0);
  }
  else if (points)
  {
    mesh.PointCopy.resize(3 * static_cast<size_t>(points->GetNumberOfPoints()));
    for (vtkIdType p = 0; p < points->GetNumberOfPoints(); ++p)
    {
      points->GetPoint(p, &mesh.PointCopy[3 * p]);
    }
    mesh.View.Points = mesh.PointCopy.data();
  }

  // Coordinates of the points the cells use: finite, and in 2D in one plane.
  double lo[3];
  double hi[3];
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = std::numeric_limits<double>::infinity();
    hi[d] = -lo[d];
  }
  const mp::Index* ids = mesh.View.Connectivity;
  for (vtkIdType i = 0; i < corners * numberOfCells; ++i)
  {
    const double* x = mesh.View.Point(ids[i]);
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
    {
      why << role << " has a point with a NaN or infinite coordinate (point " << ids[i] << ").";
      return why.str();
    }
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min(lo[d], x[d]);
      hi[d] = std::max(hi[d], x[d]);
    }
  }
  if (numberOfCells > 0 && mesh.View.Dimension == 2)
  {
    const double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]);
    if (hi[2] - lo[2] > 1e-9 * std::max(extent, std::fabs(hi[2])))
    {
      why << role << " is not planar: its triangles' z coordinates range over [" << lo[2] << ", "
          << hi[2] << "]. Triangle meshes must lie in a plane z = constant (surfaces in 3D are "
          << "not supported).";
      return why.str();
    }
    mesh.PlaneZ = 0.5 * (lo[2] + hi[2]);
  }
  return std::string();
}

/// Face neighbours from VTK's static cell links: the cell across face k
/// (opposite corner k) is the other cell using both of its end points.
void BuildNeighbors(vtkUnstructuredGrid* grid, KernelMesh& mesh)
{
  const vtkIdType n = mesh.View.NumberOfCells;
  const int corners = mesh.View.CornersPerCell();
  mesh.Neighbors.assign(corners * static_cast<size_t>(n), -1);
  mesh.View.Neighbors = mesh.Neighbors.data();
  if (n == 0)
  {
    return;
  }
  vtkNew<vtkStaticCellLinks> links;
  links->SetDataSet(grid);
  links->BuildLinks();
  std::atomic<vtkIdType> nonManifold(0);
  const mp::Index* conn = mesh.View.Connectivity;
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType c = begin; c < end; ++c)
    {
      for (int k = 0; k < corners; ++k)
      {
        // The cells around the face's first corner that hold its other corners.
        const vtkIdType first = conn[corners * c + (k + 1) % corners];
        const vtkIdType count = links->GetNcells(first);
        const vtkIdType* around = links->GetCells(first);
        vtkIdType found = -1;
        int matches = 0;
        for (vtkIdType i = 0; i < count; ++i)
        {
          const vtkIdType other = around[i];
          if (other == c)
          {
            continue;
          }
          const mp::Index* o = conn + corners * other;
          bool shares = true;
          for (int j = 2; j < corners && shares; ++j)
          {
            const mp::Index p = conn[corners * c + (k + j) % corners];
            shares = std::find(o, o + corners, p) != o + corners;
          }
          if (shares)
          {
            found = other;
            ++matches;
          }
        }
        if (matches == 1)
        {
          mesh.Neighbors[corners * c + k] = found;
        }
        else if (matches > 1)
        {
          ++nonManifold;
        }
      }
    }
  });
  mesh.NonManifoldFaces = nonManifold / 2;
}

/// The kernel's seed search, answered by vtkStaticCellLocator.
class StaticLocator : public mp::CandidateLocator
{
public:
  StaticLocator(vtkUnstructuredGrid* source, int dimension, double planeZ)
    : Dimension(dimension)
    , Z(planeZ)
  {
    this->Locator->SetDataSet(source);
    this->Locator->BuildLocator();
  }
  void FindCandidates(const double box[6], std::vector<mp::Index>& cells) override
  {
    // 2D: the kernel works in x, y; the source lies in its own plane z = Z.
    double bounds[6] = { box[0], box[1], box[2], box[3], box[4], box[5] };
    if (this->Dimension == 2)
    {
      bounds[4] = bounds[5] = this->Z;
    }
    this->Locator->FindCellsWithinBounds(bounds, this->Ids);
    cells.assign(this->Ids->begin(), this->Ids->end());
  }

private:
  int Dimension;
  double Z;
  vtkNew<vtkStaticCellLocator> Locator;
  vtkNew<vtkIdList> Ids;
};

/// A source array as contiguous doubles (a view when it already is one).
const double* AsDoubles(vtkDataArray* array, std::vector<double>& copy)
{
  vtkDoubleArray* doubles = vtkDoubleArray::SafeDownCast(array);
  if (doubles)
  {
    return doubles->GetPointer(0);
  }
  const int nc = array->GetNumberOfComponents();
  copy.resize(static_cast<size_t>(array->GetNumberOfTuples()) * nc);
  vtkSMPTools::For(0, array->GetNumberOfTuples(), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType t = begin; t < end; ++t)
    {
      for (int k = 0; k < nc; ++k)
      {
        copy[t * nc + k] = array->GetComponent(t, k);
      }
    }
  });
  return copy.data();
}

/// The pieces' points, cells and the SourceCellId / TargetCellId / measure arrays.
template <class DataSet>
vtkSmartPointer<DataSet> MakePieces(const mp::IntersectionPieces& pieces, double z,
  const char* measureName, std::function<void(DataSet*, vtkCellArray*)> setCells)
{
  auto result = vtkSmartPointer<DataSet>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const vtkIdType nv = static_cast<vtkIdType>(pieces.Points.size() / 3);
  points->SetNumberOfPoints(nv);
  for (vtkIdType v = 0; v < nv; ++v)
  {
    points->SetPoint(v, pieces.Points[3 * v], pieces.Points[3 * v + 1], pieces.Points[3 * v + 2] + z);
  }
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(pieces.Offsets.size()));
  std::copy(pieces.Offsets.begin(), pieces.Offsets.end(), offsets->GetPointer(0));
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(nv);
  for (vtkIdType v = 0; v < nv; ++v)
  {
    connectivity->SetValue(v, v);
  }
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  result->SetPoints(points);
  setCells(result, cells);

  auto idArray = [&](const char* name, const std::vector<mp::Index>& values) {
    vtkNew<vtkIdTypeArray> a;
    a->SetName(name);
    a->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
    std::copy(values.begin(), values.end(), a->GetPointer(0));
    result->GetCellData()->AddArray(a);
  };
  idArray("SourceCellId", pieces.SourceCell);
  idArray("TargetCellId", pieces.TargetCell);
  vtkNew<vtkDoubleArray> measure;
  measure->SetName(measureName);
  measure->SetNumberOfValues(static_cast<vtkIdType>(pieces.Measure.size()));
  std::copy(pieces.Measure.begin(), pieces.Measure.end(), measure->GetPointer(0));
  result->GetCellData()->AddArray(measure);
  return result;
}

/// 2D: one polygon per intersecting pair, in the target's plane.
vtkSmartPointer<vtkPolyData> MakeIntersectionPolygons(const mp::IntersectionPieces& pieces, double z)
{
  return MakePieces<vtkPolyData>(
    pieces, z, "Area", [](vtkPolyData* p, vtkCellArray* cells) { p->SetPolys(cells); });
}

/// 3D: the tetrahedra decomposing each intersection polyhedron.
vtkSmartPointer<vtkUnstructuredGrid> MakeIntersectionPolyhedra(const mp::IntersectionPieces& pieces)
{
  return MakePieces<vtkUnstructuredGrid>(pieces, 0.0, "Volume",
    [](vtkUnstructuredGrid* g, vtkCellArray* cells) { g->SetCells(VTK_TETRA, cells); });
}
} // namespace

//------------------------------------------------------------------------------
vtkMeshProjectionFilter::vtkMeshProjectionFilter()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
}

vtkMeshProjectionFilter::~vtkMeshProjectionFilter() = default;

void vtkMeshProjectionFilter::SetSourceConnection(vtkAlgorithmOutput* algOutput)
{
  this->SetInputConnection(1, algOutput);
}

void vtkMeshProjectionFilter::SetSourceData(vtkDataObject* input)
{
  this->SetInputData(1, input);
}

vtkDataObject* vtkMeshProjectionFilter::GetSource()
{
  return this->GetNumberOfInputConnections(1) < 1 ? nullptr : this->GetInputDataObject(1, 0);
}

int vtkMeshProjectionFilter::FillInputPortInformation(int vtkNotUsed(port), vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  return 1;
}

int vtkMeshProjectionFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 1 ? "vtkPolyData" : "vtkUnstructuredGrid");
  return 1;
}

int vtkMeshProjectionFilter::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // The whole source is needed wherever the target is, as in vtkResampleWithDataSet.
  vtkInformation* sourceInfo = inputVector[1]->GetInformationObject(0);
  sourceInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  sourceInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  sourceInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  inInfo->CopyEntry(outInfo, vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
  inInfo->CopyEntry(outInfo, vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES());
  inInfo->CopyEntry(outInfo, vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS());
  return 1;
}

//------------------------------------------------------------------------------
int vtkMeshProjectionFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto start = std::chrono::steady_clock::now();
  vtkUnstructuredGrid* target = vtkUnstructuredGrid::GetData(inputVector[0], 0);
  vtkUnstructuredGrid* source = vtkUnstructuredGrid::GetData(inputVector[1], 0);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  vtkPolyData* polygons = vtkPolyData::GetData(outputVector, 1);
  vtkUnstructuredGrid* polyhedra = vtkUnstructuredGrid::GetData(outputVector, 2);
  this->NumberOfIntersections = this->NumberOfIntersectionTests = 0;
  this->NumberOfLocatorQueries = 0;
  this->CoveredMeasure = this->ExecutionTime = 0;

  // 1. The output is Input as it came, whatever happens next.
  output->ShallowCopy(target);
  polygons->Initialize();
  polyhedra->Initialize();
  if (!source)
  {
    vtkErrorMacro("No Source is connected (input port 1): nothing to project.");
    return 1;
  }

  // 2. Both meshes: triangles in a plane (2D) or tetrahedra (3D), finite coordinates.
  KernelMesh targetMesh;
  KernelMesh sourceMesh;
  for (auto& item : { std::make_pair(target, &targetMesh), std::make_pair(source, &sourceMesh) })
  {
    const std::string why = WrapSimplexMesh(
      item.first, item.first == target ? "Input" : "Source", *item.second);
    if (!why.empty())
    {
      vtkErrorMacro(<< why);
      return 1;
    }
  }
  if (target->GetNumberOfCells() == 0 || source->GetNumberOfCells() == 0)
  {
    vtkWarningMacro(<< (target->GetNumberOfCells() == 0 ? "Input" : "Source")
                    << " has no cells: every projected point is invalid.");
    // An empty mesh takes the dimension of the other one.
    targetMesh.View.Dimension = sourceMesh.View.Dimension =
      std::max(target->GetNumberOfCells() ? targetMesh.View.Dimension : 2,
        source->GetNumberOfCells() ? sourceMesh.View.Dimension : 2);
  }
  else if (targetMesh.View.Dimension != sourceMesh.View.Dimension)
  {
    vtkErrorMacro(<< "Input is a " << targetMesh.View.Dimension << "D mesh ("
                  << (targetMesh.View.Dimension == 2 ? "triangles" : "tetrahedra")
                  << ") but Source is " << sourceMesh.View.Dimension << "D: both must be of "
                  << "the same dimension.");
    return 1;
  }
  else if (targetMesh.View.Dimension == 2 && targetMesh.PlaneZ != sourceMesh.PlaneZ)
  {
    vtkWarningMacro(<< "Source lies in the plane z = " << sourceMesh.PlaneZ << ", Input in z = "
                    << targetMesh.PlaneZ << "; the meshes are compared in x and y only.");
  }

  // 3. Neighbours (VTK cell links) and the seed locator (vtkStaticCellLocator).
  mp::ProjectionOptions options;
  options.KeepPieces = this->OutputIntersections;
  options.Method = this->SearchMethod == BRUTE_FORCE ? mp::SearchMethod::BruteForce
                                                     : mp::SearchMethod::AdvancingFront;
  std::unique_ptr<StaticLocator> locator;
  if (options.Method == mp::SearchMethod::AdvancingFront)
  {
    BuildNeighbors(target, targetMesh);
    BuildNeighbors(source, sourceMesh);
    if (targetMesh.NonManifoldFaces || sourceMesh.NonManifoldFaces)
    {
      vtkWarningMacro(<< "Faces shared by more than two cells (Input: "
                      << targetMesh.NonManifoldFaces << ", Source: " << sourceMesh.NonManifoldFaces
                      << ") are treated as boundaries; results stay correct but the search is slower.");
    }
    if (source->GetNumberOfCells() > 0)
    {
      locator.reset(new StaticLocator(source, sourceMesh.View.Dimension, sourceMesh.PlaneZ));
    }
  }

  // 4. Intersections, mortar matrices and the factorization of M_tt.
  mp::MortarProjector projector;
  mp::BoxGridLocator emptyLocator(sourceMesh.View); // only used when Source has no cells
  mp::CandidateLocator* seeds = locator ? static_cast<mp::CandidateLocator*>(locator.get())
                                        : static_cast<mp::CandidateLocator*>(&emptyLocator);
  if (!projector.Build(targetMesh.View, sourceMesh.View, seeds, options))
  {
    vtkErrorMacro(<< "Projection failed: " << projector.GetError());
    return 1;
  }
  const mp::SearchStatistics& stats = projector.GetStatistics();
  this->NumberOfIntersections = stats.Pieces;
  this->NumberOfIntersectionTests = stats.IntersectionTests;
  this->NumberOfLocatorQueries = stats.LocatorQueries;
  this->CoveredMeasure = projector.GetCoveredMeasure();
  if (stats.DegenerateCells > 0)
  {
    vtkWarningMacro(<< stats.DegenerateCells
                    << " cells of zero " << (targetMesh.View.Dimension == 2 ? "area" : "volume")
                    << " were ignored (they carry no part of the integrals).");
  }
  if (target->GetNumberOfCells() > 0 && source->GetNumberOfCells() > 0 &&
    projector.GetNumberOfValidPoints() == 0)
  {
    vtkWarningMacro("Source and Input do not overlap: every projected point is invalid.");
  }

  // 5. Project every numeric point array of Source.
  vtkPointData* sourcePD = source->GetPointData();
  vtkPointData* outPD = output->GetPointData();
  const vtkIdType nt = target->GetNumberOfPoints();
  std::vector<double> buffer;
  for (int i = 0; i < sourcePD->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* abstract = sourcePD->GetAbstractArray(i);
    const char* name = abstract->GetName();
    vtkDataArray* array = vtkArrayDownCast<vtkDataArray>(abstract);
    if (!array)
    {
      vtkWarningMacro(<< "Source point array '" << (name ? name : "(unnamed)")
                      << "' is not numeric (" << abstract->GetClassName() << "): skipped.");
      continue;
    }
    if (name && (std::string(name) == vtkDataSetAttributes::GhostArrayName() ||
                  std::string(name) == "vtkValidPointMask"))
    {
      continue;
    }
    vtkNew<vtkDoubleArray> projected;
    projected->SetName(name ? name : ("ProjectedArray" + std::to_string(i)).c_str());
    const int nc = array->GetNumberOfComponents();
    projected->SetNumberOfComponents(nc);
    for (int k = 0; k < nc; ++k)
    {
      if (array->GetComponentName(k))
      {
        projected->SetComponentName(k, array->GetComponentName(k));
      }
    }
    projected->SetNumberOfTuples(nt);
    if (nt > 0)
    {
      const double fill =
        this->FillWithNaN ? std::numeric_limits<double>::quiet_NaN() : this->FillValue;
      projector.Project(AsDoubles(array, buffer), nc, projected->GetPointer(0), fill);
    }
    outPD->AddArray(projected);
    if (array == sourcePD->GetScalars())
    {
      outPD->SetActiveScalars(projected->GetName());
    }
    else if (array == sourcePD->GetVectors())
    {
      outPD->SetActiveVectors(projected->GetName());
    }
  }

  // 6. Where the result is defined, and how much of each cell is covered.
  vtkNew<vtkCharArray> mask;
  mask->SetName("vtkValidPointMask");
  mask->SetNumberOfValues(nt);
  std::copy(projector.GetValidPoints().begin(), projector.GetValidPoints().end(), mask->GetPointer(0));
  outPD->AddArray(mask);
  vtkNew<vtkDoubleArray> covered;
  covered->SetName("CoveredFraction");
  covered->SetNumberOfValues(target->GetNumberOfCells());
  std::copy(projector.GetCoveredFraction().begin(), projector.GetCoveredFraction().end(),
    covered->GetPointer(0));
  output->GetCellData()->AddArray(covered);

  // 7. Optionally, the intersection polygons.
  if (this->OutputIntersections && targetMesh.View.Dimension == 2)
  {
    polygons->ShallowCopy(MakeIntersectionPolygons(projector.GetPieces(), targetMesh.PlaneZ));
  }
  else if (this->OutputIntersections)
  {
    polyhedra->ShallowCopy(MakeIntersectionPolyhedra(projector.GetPieces()));
  }
  this->ExecutionTime =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return 1;
}

//------------------------------------------------------------------------------
void vtkMeshProjectionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SearchMethod: "
     << (this->SearchMethod == BRUTE_FORCE ? "BruteForce" : "AdvancingFront") << "\n";
  os << indent << "OutputIntersections: " << (this->OutputIntersections ? "On" : "Off") << "\n";
  os << indent << "FillWithNaN: " << (this->FillWithNaN ? "On" : "Off") << "\n";
  os << indent << "FillValue: " << this->FillValue << "\n";
  os << indent << "NumberOfIntersections: " << this->NumberOfIntersections << "\n";
  os << indent << "NumberOfIntersectionTests: " << this->NumberOfIntersectionTests << "\n";
  os << indent << "NumberOfLocatorQueries: " << this->NumberOfLocatorQueries << "\n";
  os << indent << "CoveredMeasure: " << this->CoveredMeasure << "\n";
  os << indent << "ExecutionTime: " << this->ExecutionTime << "\n";
}
