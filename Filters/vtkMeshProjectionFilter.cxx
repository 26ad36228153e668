// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMeshProjectionFilter.h"

#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnstructuredGrid.h"

#include "vtkMeshProjectionMesh.h"

#include "Search/ParallelSearch.h"
#include "Transfer/MortarOperator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMeshProjectionFilter);

namespace
{
/**
 * 2D: sees both meshes in the frame of Input's plane (of Source's when
 * Input has no cells); a Source in a parallel plane is projected onto it,
 * with a `warning`. Returns an error when the planes are not parallel.
 */
std::string UseOnePlane(mpvtk::SimplexMesh& target, mpvtk::SimplexMesh& source, std::string& warning)
{
  const bool sourceOnly = target.View().NumberOfCells == 0;
  const mp::PlaneFrame& frame = sourceOnly ? source.OwnPlane() : target.OwnPlane();
  const mp::PlaneFrame& other = sourceOnly ? target.OwnPlane() : source.OwnPlane();
  std::ostringstream text;
  if (target.View().NumberOfCells > 0 && source.View().NumberOfCells > 0)
  {
    if (!frame.IsParallel(other))
    {
      const double* n = frame.GetNormal();
      const double* m = other.GetNormal();
      text << "Input and Source lie in planes that are not parallel (normals (" << n[0] << ", "
           << n[1] << ", " << n[2] << ") and (" << m[0] << ", " << m[1] << ", " << m[2]
           << ")): 2D meshes must lie in one plane.";
      return text.str();
    }
    if (std::fabs(frame.Offset() - other.Offset()) > std::max(frame.Tolerance(), other.Tolerance()))
    {
      if (frame.IsIdentity())
      {
        text << "Source lies in the plane z = " << source.OwnPlane().Offset() << ", Input in z = "
             << target.OwnPlane().Offset() << "; the meshes are compared in x and y only.";
      }
      else
      {
        text << "Source lies in a plane parallel to Input's, "
             << std::fabs(frame.Offset() - other.Offset())
             << " away; it is projected onto Input's plane.";
      }
      warning = text.str();
    }
  }
  target.UseFrame(frame);
  source.UseFrame(frame);
  return std::string();
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

int vtkMeshProjectionFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  if (port == 1)
  {
    // Optional for the executive, so that a missing Source reaches
    // RequestData: a clear error and Input passed through, rather than the
    // executive's refusal and an empty (or stale) output.
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
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
  if (vtkInformation* sourceInfo = inputVector[1]->GetInformationObject(0)) // optional port
  {
    sourceInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
    sourceInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
    sourceInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  }
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
  this->InputTime = this->NeighborsTime = this->LocatorTime = this->SearchTime = 0;
  this->AssemblyTime = this->SolveTime = this->OutputTime = 0;
  auto lap = [](std::chrono::steady_clock::time_point& since) {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - since).count();
    since = now;
    return seconds;
  };
  auto stage = start;

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
  mpvtk::SimplexMesh targetMesh;
  mpvtk::SimplexMesh sourceMesh;
  for (auto& item : { std::make_pair(target, &targetMesh), std::make_pair(source, &sourceMesh) })
  {
    const std::string why =
      item.second->Wrap(item.first, item.first == target ? "Input" : "Source");
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
    const int d = std::max(target->GetNumberOfCells() ? targetMesh.Dimension() : 2,
      source->GetNumberOfCells() ? sourceMesh.Dimension() : 2);
    targetMesh.SetDimension(d);
    sourceMesh.SetDimension(d);
  }
  else if (targetMesh.Dimension() != sourceMesh.Dimension())
  {
    vtkErrorMacro(<< "Input is a " << targetMesh.Dimension() << "D mesh ("
                  << (targetMesh.Dimension() == 2 ? "triangles" : "tetrahedra")
                  << ") but Source is " << sourceMesh.Dimension() << "D: both must be of "
                  << "the same dimension.");
    return 1;
  }
  if (targetMesh.Dimension() == 2)
  {
    std::string warning;
    const std::string error = UseOnePlane(targetMesh, sourceMesh, warning);
    if (!error.empty())
    {
      vtkErrorMacro(<< error);
      return 1;
    }
    if (!warning.empty())
    {
      vtkWarningMacro(<< warning);
    }
  }
  if (targetMesh.GhostCells() || sourceMesh.GhostCells())
  {
    vtkWarningMacro(<< "Ghost cells (Input: " << targetMesh.GhostCells() << ", Source: "
                    << sourceMesh.GhostCells() << ") are left out of the projection.");
  }

  // 3. Neighbours (VTK cell links) and the seed locator (vtkStaticCellLocator).
  mp::OperatorOptions options;
  options.KeepPieces = this->OutputIntersections;
  options.Method = this->SearchMethod == BRUTE_FORCE ? mp::SearchMethod::BruteForce
                                                     : mp::SearchMethod::AdvancingFront;
  std::unique_ptr<mp::CandidateLocator> locator;
  this->InputTime = lap(stage);
  if (mp::SearchNeedsNeighbors(options.Method))
  {
    targetMesh.BuildNeighbors();
    sourceMesh.BuildNeighbors();
    this->NeighborsTime = lap(stage);
    if (targetMesh.NonManifoldFaces() || sourceMesh.NonManifoldFaces())
    {
      vtkWarningMacro(<< "Faces shared by more than two cells (Input: "
                      << targetMesh.NonManifoldFaces() << ", Source: "
                      << sourceMesh.NonManifoldFaces()
                      << ") are treated as boundaries; results stay correct but the search is slower.");
    }
    // A Source without cells has nothing to locate: the kernel's own
    // (empty) locator answers the front's questions then.
    locator.reset(source->GetNumberOfCells() > 0
        ? static_cast<mp::CandidateLocator*>(new mpvtk::StaticLocator(source, sourceMesh))
        : new mp::BoxGridLocator(sourceMesh.View()));
    this->LocatorTime = lap(stage);
  }

  // 4. The fields: every numeric point array of Source, side by side.
  vtkPointData* sourcePD = source->GetPointData();
  std::vector<vtkDataArray*> arrays;
  int components = 0;
  for (int i = 0; i < sourcePD->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* abstract = sourcePD->GetAbstractArray(i);
    const char* name = abstract->GetName();
    vtkDataArray* array = vtkArrayDownCast<vtkDataArray>(abstract);
    if (!array)
    {
      vtkWarningMacro(<< "Source point array '" << (name ? name : "(unnamed)")
                      << "' is not numeric (" << abstract->GetClassName() << "): skipped.");
    }
    else if (!name || (std::string(name) != vtkDataSetAttributes::GhostArrayName() &&
                        std::string(name) != "vtkValidPointMask"))
    {
      if (array->GetDataType() != VTK_FLOAT && array->GetDataType() != VTK_DOUBLE)
      {
        vtkWarningMacro(<< "Source point array '" << (name ? name : "(unnamed)") << "' holds "
                        << "integers (" << array->GetClassName() << "): it is projected as "
                        << "real values, and an L2 projection of labels or ids is not "
                        << "meaningful (use Resample With Dataset for labels).");
      }
      arrays.push_back(array);
      components += array->GetNumberOfComponents();
    }
  }
  if (arrays.empty())
  {
    vtkWarningMacro("Source has no point arrays to project: only vtkValidPointMask and "
                    "CoveredFraction are computed.");
  }
  const vtkIdType ns = source->GetNumberOfPoints();
  // Never empty: a Source without points but with arrays still passes the
  // kernel a pointer to its (absent) values.
  mp::LargeVector<double> fields(std::max<size_t>(static_cast<size_t>(ns) * components, 1));
  for (int a = 0, offset = 0; a < static_cast<int>(arrays.size()); ++a)
  {
    vtkDataArray* array = arrays[a];
    const int nc = array->GetNumberOfComponents();
    vtkSMPTools::For(0, ns, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType p = begin; p < end; ++p)
      {
        for (int k = 0; k < nc; ++k)
        {
          fields[p * components + offset + k] = array->GetComponent(p, k);
        }
      }
    });
    offset += nc;
  }

  // 5. The operator from the two geometries: intersections and M_tt. The
  // filter projects its fields once, so their right-hand sides M_ts u_s are
  // summed during the search and M_ts itself is not assembled (a third
  // less time in 2D; an operator kept across time steps will assemble it).
  this->InputTime += lap(stage);
  mp::MortarOperator projection;
  options.Fields = fields.data();
  options.FieldComponents = components;
  // One range of target cells per thread of vtkSMPTools' backend (with
  // Debian's VTK: VTK_SMP_BACKEND_IN_USE=STDThread; the default backend there
  // is sequential).
  options.Runner.Tasks = vtkSMPTools::GetEstimatedNumberOfThreads();
  options.Runner.Run = [](int count, const std::function<void(int)>& task) {
    vtkSMPTools::For(0, count, 1, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType k = begin; k < end; ++k)
      {
        task(static_cast<int>(k));
      }
    });
  };
  if (!projection.Build(targetMesh.View(), sourceMesh.View(), locator.get(), options))
  {
    vtkErrorMacro(<< "Projection failed: " << projection.GetError());
    return 1;
  }
  const mp::SearchStatistics& stats = projection.GetStatistics();
  this->NumberOfIntersections = stats.Pieces;
  this->NumberOfIntersectionTests = stats.IntersectionTests;
  this->NumberOfLocatorQueries = stats.LocatorQueries;
  this->CoveredMeasure = projection.GetCoveredMeasure();
  if (stats.DegenerateTargetCells > 0 || stats.DegenerateSourceCells > 0)
  {
    vtkWarningMacro(<< "Cells of zero " << (targetMesh.Dimension() == 2 ? "area" : "volume")
                    << " (Input: " << stats.DegenerateTargetCells << ", Source: "
                    << stats.DegenerateSourceCells
                    << ") were ignored: they carry no part of the integrals.");
  }
  if (target->GetNumberOfCells() > 0 && source->GetNumberOfCells() > 0 &&
    projection.GetNumberOfValid() == 0)
  {
    vtkWarningMacro("Source and Input do not overlap: every projected point is invalid.");
  }
  if (projection.GetNumberOfOvercoveredCells() > 0)
  {
    vtkWarningMacro(<< projection.GetNumberOfOvercoveredCells()
                    << " Input cells are covered more than once: Source cells overlap each other "
                    << "(folded, inverted among their neighbours, or duplicated). The result is "
                    << "not a projection of one field there.");
  }

  // 6. Solve M_tt u_t = M_ts u_s, one output array per source array.
  const vtkIdType nt = target->GetNumberOfPoints();
  mp::LargeVector<double> values(static_cast<size_t>(nt) * components);
  const double fill =
    this->FillWithNaN ? std::numeric_limits<double>::quiet_NaN() : this->FillValue;
  if (components > 0 && !projection.Apply(fields.data(), components, values.data(), fill))
  {
    vtkErrorMacro("The mass matrix of the covered target part could not be solved.");
    return 1;
  }
  mp::LargeVector<double>().swap(fields);
  lap(stage);
  this->SearchTime = projection.GetTimings().Search;
  this->AssemblyTime = projection.GetTimings().Assembly;
  this->SolveTime = projection.GetTimings().Solve;
  vtkPointData* outPD = output->GetPointData();
  for (int a = 0, offset = 0; a < static_cast<int>(arrays.size()); ++a)
  {
    vtkDataArray* array = arrays[a];
    const int nc = array->GetNumberOfComponents();
    vtkNew<vtkDoubleArray> projected;
    projected->SetName(array->GetName() ? array->GetName()
                                        : ("ProjectedArray" + std::to_string(a)).c_str());
    projected->SetNumberOfComponents(nc);
    for (int k = 0; k < nc; ++k)
    {
      if (array->GetComponentName(k))
      {
        projected->SetComponentName(k, array->GetComponentName(k));
      }
    }
    projected->SetNumberOfTuples(nt);
    double* out = projected->GetPointer(0);
    for (vtkIdType p = 0; p < nt; ++p)
    {
      std::copy_n(&values[p * components + offset], nc, out + p * nc);
    }
    offset += nc;
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

  // 7. Where the result is defined, and how much of each cell is covered.
  vtkNew<vtkCharArray> mask;
  mask->SetName("vtkValidPointMask");
  mask->SetNumberOfValues(nt);
  std::copy(projection.GetValid().begin(), projection.GetValid().end(), mask->GetPointer(0));
  outPD->AddArray(mask);
  vtkNew<vtkDoubleArray> covered;
  covered->SetName("CoveredFraction");
  covered->SetNumberOfValues(target->GetNumberOfCells());
  covered->Fill(0.0); // ghost cells
  const std::vector<double>& fraction = projection.GetCoveredFraction();
  for (size_t c = 0; c < fraction.size(); ++c)
  {
    covered->SetValue(targetMesh.ToVTK(static_cast<mp::Index>(c)), fraction[c]);
  }
  output->GetCellData()->AddArray(covered);

  // 8. Optionally, the intersection pieces.
  if (this->OutputIntersections && targetMesh.Dimension() == 2)
  {
    polygons->ShallowCopy(
      mpvtk::MakeIntersectionPolygons(projection.GetPieces(), targetMesh, sourceMesh));
  }
  else if (this->OutputIntersections)
  {
    polyhedra->ShallowCopy(
      mpvtk::MakeIntersectionPolyhedra(projection.GetPieces(), targetMesh, sourceMesh));
  }
  this->OutputTime = lap(stage);
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
  os << indent << "InputTime: " << this->InputTime << "\n";
  os << indent << "NeighborsTime: " << this->NeighborsTime << "\n";
  os << indent << "LocatorTime: " << this->LocatorTime << "\n";
  os << indent << "SearchTime: " << this->SearchTime << "\n";
  os << indent << "AssemblyTime: " << this->AssemblyTime << "\n";
  os << indent << "SolveTime: " << this->SolveTime << "\n";
  os << indent << "OutputTime: " << this->OutputTime << "\n";
}
