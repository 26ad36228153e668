// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMeshProjectionFilter.h"

#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkCommand.h"
#include "vtkDataArraySelection.h"
#include "vtkIdTypeArray.h"
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

#include "Geometry/Measures.h"
#include "Search/ParallelSearch.h"
#include "Transfer/MortarOperator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <thread>
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

/// A 64-bit fingerprint of an array's values (not of its address: readers
/// build new arrays at every time step).
struct Fingerprint
{
  std::uint64_t Hash = 0x243F6A8885A308D3ull;

  void Add(std::uint64_t word)
  {
    this->Hash ^= word + 0x9E3779B97F4A7C15ull + (this->Hash << 6) + (this->Hash >> 2);
    this->Hash *= 0xBF58476D1CE4E5B9ull;
    this->Hash ^= this->Hash >> 31;
  }
  void Add(const void* data, size_t bytes)
  {
    const unsigned char* b = static_cast<const unsigned char*>(data);
    std::uint64_t h = this->Hash ^ bytes;
    size_t i = 0;
    for (; i + 8 <= bytes; i += 8)
    {
      std::uint64_t w;
      std::memcpy(&w, b + i, 8);
      h = (h ^ w) * 0x100000001B3ull;
      h ^= h >> 29;
    }
    std::uint64_t last = 0;
    std::memcpy(&last, b + i, bytes - i);
    this->Add(h ^ last);
  }
  void Add(vtkDataArray* array)
  {
    if (!array)
    {
      this->Add(std::uint64_t(0));
      return;
    }
    this->Add(static_cast<std::uint64_t>(array->GetDataType()));
    this->Add(static_cast<std::uint64_t>(array->GetNumberOfValues()));
    if (array->HasStandardMemoryLayout())
    {
      this->Add(array->GetVoidPointer(0),
        static_cast<size_t>(array->GetNumberOfValues()) * array->GetDataTypeSize());
      return;
    }
    const int nc = array->GetNumberOfComponents();
    for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
    {
      for (int k = 0; k < nc; ++k)
      {
        const double v = array->GetComponent(t, k);
        this->Add(&v, sizeof v);
      }
    }
  }
  /// Points, cells, cell types and ghost cells: all the operator depends on.
  void Add(vtkUnstructuredGrid* grid)
  {
    this->Add(grid->GetPoints() ? grid->GetPoints()->GetData() : nullptr);
    vtkCellArray* cells = grid->GetCells();
    this->Add(cells ? cells->GetOffsetsArray() : nullptr);
    this->Add(cells ? cells->GetConnectivityArray() : nullptr);
    this->Add(grid->GetCellTypesArray());
    this->Add(grid->GetCellGhostArray());
  }
};

/// vtkDataObject's attribute type of the filter's associations: 0 points, 1 cells.
int AttributeType(int association)
{
  return association == 0 ? vtkDataObject::POINT : vtkDataObject::CELL;
}

/// The spaces of the four transfers (vtkMeshProjectionFilter::Transfers).
mp::SpaceType TargetSpaceOf(int transfer)
{
  return transfer == 0 || transfer == 3 ? mp::SpaceType::P1 : mp::SpaceType::P0;
}
mp::SpaceType SourceSpaceOf(int transfer)
{
  return transfer <= 1 ? mp::SpaceType::P1 : mp::SpaceType::P0;
}
const char* TransferName(int transfer)
{
  static const char* names[] = { "points to points", "points to cells", "cells to cells",
    "cells to points" };
  return names[transfer];
}

/// The Source arrays of one association, gathered side by side.
struct Gathered
{
  std::vector<vtkDataArray*> Arrays;
  int Components = 0;
  mp::LargeVector<double> Values; ///< functions x Components
  std::string Key;                ///< names and components: which solution a warm start may reuse
};
} // namespace

/// What the filter keeps between executions.
struct vtkMeshProjectionFilter::Internals
{
  vtkNew<vtkDataArraySelection> PointArrays;
  vtkNew<vtkDataArraySelection> CellArrays;
  bool Listing = false; ///< the filter is adding Source's arrays to the selections

  /// The selection of point (association 0) or cell (1) arrays.
  vtkDataArraySelection* Selection(int association)
  {
    return association == 0 ? this->PointArrays.GetPointer() : this->CellArrays.GetPointer();
  }
  std::set<std::string> Warned; ///< integer arrays already warned about
  bool AssembleNext = false;    ///< GetMatrix asked for M_ts
  bool HasFingerprint = false;
  std::uint64_t GeometryFingerprint = 0;
  struct Kept
  {
    std::unique_ptr<mp::MortarOperator> Operator;
    std::string SolutionKey;
    mp::LargeVector<double> Solution; ///< the last projection (warm start)
  };
  Kept Operators[4];
  /// For GetMatrix: VTK ids of the kernel cells (empty: the same).
  std::vector<vtkIdType> TargetCells, SourceCells;
  vtkIdType TargetCellCount = 0, SourceCellCount = 0;

  void Clear()
  {
    for (Kept& k : this->Operators)
    {
      k = Kept();
    }
    this->HasFingerprint = false;
  }
};

//------------------------------------------------------------------------------
vtkMeshProjectionFilter::vtkMeshProjectionFilter()
  : Internal(new Internals)
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
  // All arrays, including those that appear later (new time steps, new
  // inputs), unless disabled by name.
  this->Internal->PointArrays->SetUnknownArraySetting(1);
  this->Internal->CellArrays->SetUnknownArraySetting(1);
  // A change of selection re-executes the filter; the arrays the filter
  // lists itself (ListSourceArrays) do not.
  for (vtkDataArraySelection* selection :
    { this->Internal->PointArrays.GetPointer(), this->Internal->CellArrays.GetPointer() })
  {
    selection->AddObserver(vtkCommand::ModifiedEvent, this, &vtkMeshProjectionFilter::SelectionModified);
  }
}

void vtkMeshProjectionFilter::SelectionModified()
{
  if (!this->Internal->Listing)
  {
    this->Modified();
  }
}

void vtkMeshProjectionFilter::ListSourceArrays(vtkDataObject* data)
{
  vtkDataSet* source = vtkDataSet::SafeDownCast(data);
  if (!source)
  {
    return;
  }
  this->Internal->Listing = true;
  for (int association = 0; association < 2; ++association)
  {
    vtkDataSetAttributes* attributes = source->GetAttributes(AttributeType(association));
    vtkDataArraySelection* selection = this->Internal->Selection(association);
    for (int i = 0; i < attributes->GetNumberOfArrays(); ++i)
    {
      const char* name = attributes->GetArrayName(i);
      if (name && attributes->GetArray(i) && !selection->ArrayExists(name) &&
        std::string(name) != vtkDataSetAttributes::GhostArrayName() &&
        std::string(name) != "vtkValidPointMask" && std::string(name) != "vtkValidCellMask")
      {
        selection->AddArray(name, selection->GetUnknownArraySetting() != 0);
      }
    }
  }
  this->Internal->Listing = false;
}

vtkMeshProjectionFilter::~vtkMeshProjectionFilter()
{
  delete this->Internal;
}

vtkDataArraySelection* vtkMeshProjectionFilter::GetPointDataArraySelection()
{
  return this->Internal->PointArrays;
}

vtkDataArraySelection* vtkMeshProjectionFilter::GetCellDataArraySelection()
{
  return this->Internal->CellArrays;
}

vtkIdType vtkMeshProjectionFilter::GetOperatorMemory()
{
  size_t bytes = 0;
  for (const Internals::Kept& k : this->Internal->Operators)
  {
    if (k.Operator)
    {
      bytes += k.Operator->MemoryBytes() + k.Solution.capacity() * sizeof(double);
    }
  }
  return static_cast<vtkIdType>(bytes);
}

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

int vtkMeshProjectionFilter::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // The output varies in time when either input does: it advertises the
  // union of their time steps and the hull of their ranges (by default only
  // Input's would be copied, and a time-varying Source was never asked for
  // another time).
  using SDDP = vtkStreamingDemandDrivenPipeline;
  std::vector<double> steps;
  double range[2] = { 0, 0 };
  bool hasRange = false;
  for (int port = 0; port < 2; ++port)
  {
    vtkInformation* info = inputVector[port]->GetInformationObject(0);
    if (!info)
    {
      continue;
    }
    if (info->Has(SDDP::TIME_STEPS()))
    {
      const double* t = info->Get(SDDP::TIME_STEPS());
      steps.insert(steps.end(), t, t + info->Length(SDDP::TIME_STEPS()));
    }
    if (info->Has(SDDP::TIME_RANGE()))
    {
      const double* r = info->Get(SDDP::TIME_RANGE());
      range[0] = hasRange ? std::min(range[0], r[0]) : r[0];
      range[1] = hasRange ? std::max(range[1], r[1]) : r[1];
      hasRange = true;
    }
  }
  // Source's arrays as far as known (its last output), for ParaView's
  // array selection lists; RequestData completes them.
  if (vtkInformation* sourceInfo = inputVector[1]->GetInformationObject(0))
  {
    this->ListSourceArrays(sourceInfo->Get(vtkDataObject::DATA_OBJECT()));
  }
  std::sort(steps.begin(), steps.end());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  for (int port = 0; port < outputVector->GetNumberOfInformationObjects(); ++port)
  {
    vtkInformation* out = outputVector->GetInformationObject(port);
    if (steps.empty())
    {
      out->Remove(SDDP::TIME_STEPS());
    }
    else
    {
      out->Set(SDDP::TIME_STEPS(), steps.data(), static_cast<int>(steps.size()));
    }
    if (hasRange)
    {
      out->Set(SDDP::TIME_RANGE(), range, 2);
    }
    else
    {
      out->Remove(SDDP::TIME_RANGE());
    }
  }
  return 1;
}

int vtkMeshProjectionFilter::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  // The whole source is needed wherever the target is, as in vtkResampleWithDataSet.
  if (vtkInformation* sourceInfo = inputVector[1]->GetInformationObject(0)) // optional port
  {
    sourceInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
    sourceInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
    sourceInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    // Both inputs at the time asked of the output.
    if (outInfo->Has(SDDP::UPDATE_TIME_STEP()))
    {
      sourceInfo->Set(SDDP::UPDATE_TIME_STEP(), outInfo->Get(SDDP::UPDATE_TIME_STEP()));
    }
  }
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  inInfo->CopyEntry(outInfo, SDDP::UPDATE_PIECE_NUMBER());
  inInfo->CopyEntry(outInfo, SDDP::UPDATE_NUMBER_OF_PIECES());
  inInfo->CopyEntry(outInfo, SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS());
  if (outInfo->Has(SDDP::UPDATE_TIME_STEP()))
  {
    inInfo->Set(SDDP::UPDATE_TIME_STEP(), outInfo->Get(SDDP::UPDATE_TIME_STEP()));
  }
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
  this->OperatorReused = false;
  this->NumberOfOperatorsBuilt = 0;
  Internals& kept = *this->Internal;
  auto lap = [](std::chrono::steady_clock::time_point& since) {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - since).count();
    since = now;
    return seconds;
  };
  auto stage = start;
  // Progress events only from the thread that runs the pipeline (the GUI
  // handles them there); the abort flag is read from any thread.
  const std::thread::id pipelineThread = std::this_thread::get_id();
  auto progress = [this, pipelineThread](double amount) {
    if (std::this_thread::get_id() == pipelineThread)
    {
      this->UpdateProgress(amount);
    }
    return this->GetAbortExecute() == 0;
  };
  auto aborted = [&]() {
    output->ShallowCopy(target);
    polygons->Initialize();
    polyhedra->Initialize();
    vtkWarningMacro("Aborted: the output is Input as it came.");
    return 1;
  };

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

  this->ListSourceArrays(source);
  // 3. The fields: the selected numeric arrays of Source, side by side, in
  // the kernel's numbering (points: the same; cells: without ghosts).
  Gathered fields[2]; // 0: point arrays (P1), 1: cell arrays (P0)
  for (int association = 0; association < 2; ++association)
  {
    vtkDataSetAttributes* data = source->GetAttributes(AttributeType(association));
    vtkDataArraySelection* selection = kept.Selection(association);
    const char* kind = association == 0 ? "point" : "cell";
    Gathered& g = fields[association];
    for (int i = 0; i < data->GetNumberOfArrays(); ++i)
    {
      vtkAbstractArray* abstract = data->GetAbstractArray(i);
      const char* name = abstract->GetName();
      const std::string label = name ? name : "(unnamed)";
      if (label == vtkDataSetAttributes::GhostArrayName() || label == "vtkValidPointMask" ||
        label == "vtkValidCellMask" || (name && !selection->ArrayIsEnabled(name)))
      {
        continue;
      }
      // Ids of the Source's own points and cells are not fields.
      if (abstract == data->GetGlobalIds() || abstract == data->GetPedigreeIds() ||
        label == "vtkOriginalPointIds" || label == "vtkOriginalCellIds")
      {
        continue;
      }
      vtkDataArray* array = vtkArrayDownCast<vtkDataArray>(abstract);
      if (!array)
      {
        vtkWarningMacro(<< "Source " << kind << " array '" << label << "' is not numeric ("
                        << abstract->GetClassName() << "): skipped.");
        continue;
      }
      if (array->GetDataType() != VTK_FLOAT && array->GetDataType() != VTK_DOUBLE &&
        kept.Warned.insert(std::string(kind) + "/" + label).second) // once per array, not per step
      {
        vtkWarningMacro(<< "Source " << kind << " array '" << label << "' holds integers ("
                        << array->GetClassName() << "): it is projected as real values (a 0/1 "
                        << "indicator becomes a covered fraction, but labels and ids do not "
                        << "carry over: use Resample With Dataset for those, or deselect it).");
      }
      g.Arrays.push_back(array);
      g.Components += array->GetNumberOfComponents();
      g.Key += label + "/" + std::to_string(array->GetNumberOfComponents()) + ";";
    }
  }
  const bool extensive = this->CellDataQuantity == EXTENSIVE;
  fields[1].Key += extensive ? "extensive" : "intensive";
  // Which transfers run: pts->pts, pts->cells, cells->cells, cells->pts.
  bool used[4] = { fields[0].Components > 0 && (this->PointDataTarget & TO_POINTS),
    fields[0].Components > 0 && (this->PointDataTarget & TO_CELLS),
    fields[1].Components > 0 && (this->CellDataTarget & TO_CELLS),
    fields[1].Components > 0 && (this->CellDataTarget & TO_POINTS) };
  const bool any = used[0] || used[1] || used[2] || used[3];
  if (!any)
  {
    vtkWarningMacro("Source has no arrays to project (or none selected): only "
                    "vtkValidPointMask and CoveredFraction are computed.");
  }
  for (int association = 0; association < 2; ++association)
  {
    Gathered& g = fields[association];
    if (g.Components == 0)
    {
      continue;
    }
    const mp::Index n = association == 0 ? source->GetNumberOfPoints()
                                         : mp::SpaceSize(mp::SpaceType::P0, sourceMesh.View());
    g.Values.resize(std::max<size_t>(static_cast<size_t>(n) * g.Components, 1));
    std::vector<double> measure;
    if (association == 1 && extensive)
    {
      measure = mp::ParentMeasures(sourceMesh.View());
    }
    for (int a = 0, offset = 0; a < static_cast<int>(g.Arrays.size()); ++a)
    {
      vtkDataArray* array = g.Arrays[a];
      const int nc = array->GetNumberOfComponents();
      const int width = g.Components;
      vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
        for (vtkIdType f = begin; f < end; ++f)
        {
          const vtkIdType tuple = association == 0 ? f : sourceMesh.ToVTK(f);
          // Extensive values become densities (total / measure).
          const double scale = measure.empty() ? 1.0 : (measure[f] > 0 ? 1.0 / measure[f] : 0.0);
          for (int k = 0; k < nc; ++k)
          {
            g.Values[f * width + offset + k] = scale * array->GetComponent(tuple, k);
          }
        }
      });
      offset += nc;
    }
  }
  this->InputTime = lap(stage);
  if (!progress(0.05))
  {
    return aborted();
  }

  // 4. The operators: kept ones while neither mesh changed, else built.
  Fingerprint print;
  print.Add(target);
  print.Add(source);
  print.Add(static_cast<std::uint64_t>(this->SearchMethod));
  print.Add(static_cast<std::uint64_t>(this->OutputIntersections));
  const bool sameGeometry =
    this->CacheOperator && kept.HasFingerprint && kept.GeometryFingerprint == print.Hash;
  if (!sameGeometry)
  {
    kept.Clear();
  }
  kept.HasFingerprint = this->CacheOperator;
  kept.GeometryFingerprint = print.Hash;
  // The operator that gives the mask and coverage when nothing is projected.
  if (!any)
  {
    used[0] = true;
  }
  // Assembled (M_ts stored: any field, local bounds, matrices to read out)
  // when it will pay: bounds need it; with CacheOperator, when an input
  // varies in time or the meshes are those of the last execution (or
  // GetMatrix asks). Else the fields' right-hand sides are summed during the
  // search and M_ts is never formed (a one-off run in about half the time).
  using SDDP = vtkStreamingDemandDrivenPipeline;
  bool timeVarying = false;
  for (int port = 0; port < 2; ++port)
  {
    vtkInformation* info = inputVector[port]->GetInformationObject(0);
    timeVarying = timeVarying ||
      (info && info->Has(SDDP::TIME_STEPS()) && info->Length(SDDP::TIME_STEPS()) > 1);
  }
  const bool assembled = this->PreserveBounds ||
    (this->CacheOperator && (timeVarying || sameGeometry || kept.AssembleNext));
  kept.AssembleNext = false;
  mp::OperatorOptions options;
  options.KeepPieces = this->OutputIntersections;
  options.Method = this->SearchMethod == BRUTE_FORCE ? mp::SearchMethod::BruteForce
                                                     : mp::SearchMethod::AdvancingFront;
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
  std::unique_ptr<mp::CandidateLocator> locator;
  bool searchReady = false;
  int toBuild = 0;
  for (int t = 0; t < 4; ++t)
  {
    toBuild += used[t] && !kept.Operators[t].Operator;
  }
  std::unique_ptr<mp::MortarOperator> fresh[4];
  const mp::MortarOperator* operators[4] = {};
  double built = 0;
  for (int t = 0; t < 4; ++t)
  {
    if (!used[t])
    {
      continue;
    }
    if (kept.Operators[t].Operator)
    {
      operators[t] = kept.Operators[t].Operator.get();
      continue;
    }
    if (!searchReady && mp::SearchNeedsNeighbors(options.Method))
    {
      // Neighbours (VTK cell links) and the seed locator (vtkStaticCellLocator).
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
      if (!progress(0.15))
      {
        return aborted();
      }
    }
    searchReady = true;
    const Gathered& g = fields[SourceSpaceOf(t) == mp::SpaceType::P1 ? 0 : 1];
    options.TargetSpace = TargetSpaceOf(t);
    options.SourceSpace = SourceSpaceOf(t);
    options.Fields = assembled || g.Components == 0 ? nullptr : g.Values.data();
    options.FieldComponents = assembled ? 0 : g.Components;
    const double from = 0.15 + 0.7 * built / toBuild;
    options.Progress = [&progress, from, toBuild](double f) {
      return progress(from + 0.7 * f / toBuild);
    };
    fresh[t].reset(new mp::MortarOperator);
    const bool ok = fresh[t]->Build(targetMesh.View(), sourceMesh.View(), locator.get(), options);
    if (!ok && fresh[t]->GetError() == "stopped")
    {
      return aborted();
    }
    if (!ok)
    {
      vtkErrorMacro(<< "Projection failed: " << fresh[t]->GetError());
      output->ShallowCopy(target);
      return 1;
    }
    operators[t] = fresh[t].get();
    this->SearchTime += fresh[t]->GetTimings().Search;
    this->AssemblyTime += fresh[t]->GetTimings().Assembly;
    ++this->NumberOfOperatorsBuilt;
    built += 1;
    lap(stage);
  }
  this->OperatorReused = this->NumberOfOperatorsBuilt == 0;
  const mp::MortarOperator* first = nullptr; // coverage, statistics, pieces
  for (const mp::MortarOperator* op : operators)
  {
    first = first ? first : op;
  }
  const mp::SearchStatistics& stats = first->GetStatistics();
  this->NumberOfIntersections = stats.Pieces;
  this->NumberOfIntersectionTests = stats.IntersectionTests;
  this->NumberOfLocatorQueries = stats.LocatorQueries;
  this->CoveredMeasure = first->GetCoveredMeasure();
  if (!this->OperatorReused)
  {
    if (stats.DegenerateTargetCells > 0 || stats.DegenerateSourceCells > 0)
    {
      vtkWarningMacro(<< "Cells of zero " << (targetMesh.Dimension() == 2 ? "area" : "volume")
                      << " (Input: " << stats.DegenerateTargetCells << ", Source: "
                      << stats.DegenerateSourceCells
                      << ") were ignored: they carry no part of the integrals.");
    }
    if (target->GetNumberOfCells() > 0 && source->GetNumberOfCells() > 0 &&
      first->GetCoveredMeasure() == 0)
    {
      vtkWarningMacro("Source and Input do not overlap: every projected value is invalid.");
    }
    if (first->GetNumberOfOvercoveredCells() > 0)
    {
      vtkWarningMacro(<< first->GetNumberOfOvercoveredCells()
                      << " Input cells are covered more than once: Source cells overlap each other "
                      << "(folded, inverted among their neighbours, or duplicated). The result is "
                      << "not a projection of one field there.");
    }
  }
  if (!progress(0.85))
  {
    return aborted();
  }

  // 5. Apply: M_ts u_s, then M_tt (consistent, from the previous step's
  // solution when the same arrays were projected with the same operator)
  // or its row sums (lumped); bounds when asked.
  const double fill =
    this->FillWithNaN ? std::numeric_limits<double>::quiet_NaN() : this->FillValue;
  mp::LargeVector<double> results[4];
  for (int t = 0; t < 4; ++t)
  {
    const Gathered& g = fields[SourceSpaceOf(t) == mp::SpaceType::P1 ? 0 : 1];
    if (!operators[t] || g.Components == 0)
    {
      continue;
    }
    const mp::MortarOperator& op = *operators[t];
    Internals::Kept& k = kept.Operators[t];
    mp::LargeVector<double>& values = results[t];
    const size_t size = static_cast<size_t>(op.GetNumberOfTargetFunctions()) * g.Components;
    mp::ApplyOptions apply;
    apply.Mass = this->MassMatrix == LUMPED_MASS ? mp::MassType::Lumped : mp::MassType::Consistent;
    apply.Bounded = this->PreserveBounds;
    if (!fresh[t] && k.SolutionKey == g.Key && k.Solution.size() == size)
    {
      values.assign(k.Solution.begin(), k.Solution.end());
      apply.Solve.StartFromX = true;
    }
    else
    {
      values.resize(size);
    }
    if (!op.Apply(g.Values.data(), g.Components, values.data(), fill, apply))
    {
      vtkErrorMacro(<< "The projection of " << TransferName(t) << " failed: the mass matrix of "
                    << "the covered target part could not be solved.");
      output->ShallowCopy(target);
      kept.Clear();
      return 1;
    }
    this->SolveTime += op.GetTimings().Solve;
    if (this->CacheOperator)
    {
      k.SolutionKey = g.Key;
      k.Solution.assign(values.begin(), values.end());
    }
  }
  // Kept for the next execution (and GetMatrix), or dropped; so are those
  // this execution did not use.
  for (int t = 0; t < 4; ++t)
  {
    if (fresh[t] && this->CacheOperator && fresh[t]->HasMixedMass())
    {
      kept.Operators[t].Operator = std::move(fresh[t]);
    }
    else if (!used[t] || !this->CacheOperator)
    {
      kept.Operators[t] = Internals::Kept();
    }
  }
  kept.TargetCells.clear();
  kept.SourceCells.clear();
  for (mp::Index c = 0; targetMesh.GhostCells() && c < targetMesh.View().NumberOfCells; ++c)
  {
    kept.TargetCells.push_back(targetMesh.ToVTK(c));
  }
  for (mp::Index c = 0; sourceMesh.GhostCells() && c < sourceMesh.View().NumberOfCells; ++c)
  {
    kept.SourceCells.push_back(sourceMesh.ToVTK(c));
  }
  kept.TargetCellCount = target->GetNumberOfCells();
  kept.SourceCellCount = source->GetNumberOfCells();
  if (!progress(0.95))
  {
    return aborted();
  }
  lap(stage);

  // 6. One output array per projected array.
  const vtkIdType nt = target->GetNumberOfPoints();
  const vtkIdType ntc = target->GetNumberOfCells();
  const mp::Index kernelCells = targetMesh.View().NumberOfCells;
  vtkPointData* outPD = output->GetPointData();
  vtkCellData* outCD = output->GetCellData();
  std::vector<std::string> pointNames, cellNames; // written by the main transfers
  for (int t : { 0, 2, 1, 3 })
  {
    const Gathered& g = fields[SourceSpaceOf(t) == mp::SpaceType::P1 ? 0 : 1];
    if (results[t].empty())
    {
      continue;
    }
    const bool toPoints = TargetSpaceOf(t) == mp::SpaceType::P1;
    const bool fromCells = SourceSpaceOf(t) == mp::SpaceType::P0;
    const bool totals = t == 2 && extensive; // densities back to totals
    const std::vector<double>& covered = operators[t]->GetCoveredIntegrals();
    vtkDataSetAttributes* sourceData = source->GetAttributes(AttributeType(fromCells ? 1 : 0));
    vtkDataSetAttributes* outData = output->GetAttributes(AttributeType(toPoints ? 0 : 1));
    std::vector<std::string>& written = toPoints ? pointNames : cellNames;
    const bool main = t == 0 || t == 2;
    for (int a = 0, offset = 0; a < static_cast<int>(g.Arrays.size()); ++a)
    {
      vtkDataArray* array = g.Arrays[a];
      const int nc = array->GetNumberOfComponents();
      std::string name = array->GetName() ? array->GetName()
                                          : (fromCells ? "ProjectedCellArray" : "ProjectedArray") +
          std::to_string(a);
      if (!main && std::find(written.begin(), written.end(), name) != written.end())
      {
        name += fromCells ? " (from cells)" : " (from points)";
      }
      written.push_back(name);
      vtkNew<vtkDoubleArray> projected;
      projected->SetName(name.c_str());
      projected->SetNumberOfComponents(nc);
      for (int k = 0; k < nc; ++k)
      {
        if (array->GetComponentName(k))
        {
          projected->SetComponentName(k, array->GetComponentName(k));
        }
      }
      const mp::LargeVector<double>& values = results[t];
      const int width = g.Components;
      if (toPoints)
      {
        projected->SetNumberOfTuples(nt);
        double* out = projected->GetPointer(0);
        for (vtkIdType p = 0; p < nt; ++p)
        {
          std::copy_n(&values[p * width + offset], nc, out + p * nc);
        }
      }
      else
      {
        projected->SetNumberOfTuples(ntc);
        projected->Fill(fill); // ghost cells
        double* out = projected->GetPointer(0);
        for (mp::Index c = 0; c < kernelCells; ++c)
        {
          const double scale = totals && operators[t]->GetValid()[c] ? covered[c] : 1.0;
          double* o = out + targetMesh.ToVTK(c) * nc;
          for (int k = 0; k < nc; ++k)
          {
            o[k] = scale * values[c * width + offset + k];
          }
        }
      }
      offset += nc;
      outData->AddArray(projected);
      if (main && array == sourceData->GetScalars())
      {
        outData->SetActiveScalars(projected->GetName());
      }
      else if (main && array == sourceData->GetVectors())
      {
        outData->SetActiveVectors(projected->GetName());
      }
    }
  }

  // 7. Where the result is defined, and how much of each cell is covered.
  const std::vector<double>& fraction = first->GetCoveredFraction();
  vtkNew<vtkCharArray> mask;
  mask->SetName("vtkValidPointMask");
  mask->SetNumberOfValues(nt);
  const mp::MortarOperator* onPoints = operators[0] ? operators[0] : operators[3];
  if (onPoints)
  {
    std::copy(onPoints->GetValid().begin(), onPoints->GetValid().end(), mask->GetPointer(0));
  }
  else
  {
    // A point is valid when a cell around it meets the source.
    mask->Fill(0);
    for (mp::Index c = 0; c < kernelCells; ++c)
    {
      if (fraction[c] > 0)
      {
        const mp::Index* p = targetMesh.View().Cell(c);
        for (int k = 0; k < targetMesh.View().CornersPerCell(); ++k)
        {
          mask->SetValue(p[k], 1);
        }
      }
    }
  }
  outPD->AddArray(mask);
  if (const mp::MortarOperator* onCells = operators[1] ? operators[1] : operators[2])
  {
    vtkNew<vtkCharArray> cellMask;
    cellMask->SetName("vtkValidCellMask");
    cellMask->SetNumberOfValues(ntc);
    cellMask->Fill(0); // ghost cells
    for (mp::Index c = 0; c < kernelCells; ++c)
    {
      cellMask->SetValue(targetMesh.ToVTK(c), onCells->GetValid()[c]);
    }
    outCD->AddArray(cellMask);
  }
  vtkNew<vtkDoubleArray> covered;
  covered->SetName("CoveredFraction");
  covered->SetNumberOfValues(ntc);
  covered->Fill(0.0); // ghost cells
  for (size_t c = 0; c < fraction.size(); ++c)
  {
    covered->SetValue(targetMesh.ToVTK(static_cast<mp::Index>(c)), fraction[c]);
  }
  outCD->AddArray(covered);

  // 8. Optionally, the intersection pieces.
  if (this->OutputIntersections && targetMesh.Dimension() == 2)
  {
    polygons->ShallowCopy(
      mpvtk::MakeIntersectionPolygons(first->GetPieces(), targetMesh, sourceMesh));
  }
  else if (this->OutputIntersections)
  {
    polyhedra->ShallowCopy(
      mpvtk::MakeIntersectionPolyhedra(first->GetPieces(), targetMesh, sourceMesh));
  }
  this->OutputTime = lap(stage);
  this->ExecutionTime =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
vtkIdType vtkMeshProjectionFilter::GetMatrix(int transfer, int matrix, vtkIdTypeArray* rowStart,
  vtkIdTypeArray* columns, vtkDoubleArray* values)
{
  if (transfer >= 0 && transfer <= 3 && !this->Internal->Operators[transfer].Operator &&
    this->CacheOperator && this->GetNumberOfInputConnections(0) > 0 && this->GetSource())
  {
    // The last execution summed its right-hand sides without forming M_ts
    // (a one-off run): execute again, assembling it.
    this->Internal->AssembleNext = true;
    this->Modified();
    this->Update();
  }
  if (transfer < 0 || transfer > 3 || !rowStart || !columns || !values ||
    !this->Internal->Operators[transfer].Operator)
  {
    vtkErrorMacro(<< "No operator of "
                  << (transfer >= 0 && transfer <= 3 ? TransferName(transfer) : "that number")
                  << " is kept: run the filter with CacheOperator on and that transfer in use.");
    return -1;
  }
  const mp::MortarOperator& op = *this->Internal->Operators[transfer].Operator;
  const mp::CsrMatrix& m = matrix == MIXED_MASS ? op.GetMixedMass() : op.GetTargetMass();
  // Kernel cells are the non-ghost cells in order: map P0 rows and columns
  // to VTK cell ids (empty rows for ghost cells).
  const bool cellRows = TargetSpaceOf(transfer) == mp::SpaceType::P0;
  const bool cellColumns =
    matrix == MIXED_MASS ? SourceSpaceOf(transfer) == mp::SpaceType::P0 : cellRows;
  const std::vector<vtkIdType>& rowMap = this->Internal->TargetCells;
  const std::vector<vtkIdType>& columnMap =
    matrix == MIXED_MASS ? this->Internal->SourceCells : this->Internal->TargetCells;
  const vtkIdType rows = cellRows && !rowMap.empty() ? this->Internal->TargetCellCount : m.Rows;
  vtkIdType ncolumns = m.Columns;
  if (cellColumns && !columnMap.empty())
  {
    ncolumns = matrix == MIXED_MASS ? this->Internal->SourceCellCount : this->Internal->TargetCellCount;
  }
  rowStart->SetNumberOfComponents(1);
  rowStart->SetNumberOfTuples(rows + 1);
  columns->SetNumberOfComponents(1);
  columns->SetNumberOfTuples(m.NonZeros());
  values->SetNumberOfComponents(1);
  values->SetNumberOfTuples(m.NonZeros());
  vtkIdType row = 0;
  rowStart->SetValue(0, 0);
  for (mp::Index i = 0; i < m.Rows; ++i)
  {
    const vtkIdType vtkRow = cellRows && !rowMap.empty() ? rowMap[i] : i;
    while (row < vtkRow)
    {
      rowStart->SetValue(++row, m.RowStart[i]);
    }
    for (mp::Index p = m.RowStart[i]; p < m.RowStart[i + 1]; ++p)
    {
      const vtkIdType c = m.ColumnIndex[p];
      columns->SetValue(p, cellColumns && !columnMap.empty() ? columnMap[c] : c);
      values->SetValue(p, m.Values[p]);
    }
    rowStart->SetValue(++row, m.RowStart[i + 1]);
  }
  while (row < rows)
  {
    rowStart->SetValue(++row, m.NonZeros());
  }
  return ncolumns;
}

bool vtkMeshProjectionFilter::WriteMatrixMarket(const char* fileName, int transfer, int matrix)
{
  vtkNew<vtkIdTypeArray> rowStart;
  vtkNew<vtkIdTypeArray> columns;
  vtkNew<vtkDoubleArray> values;
  const vtkIdType ncolumns = this->GetMatrix(transfer, matrix, rowStart, columns, values);
  if (ncolumns < 0)
  {
    return false;
  }
  std::ofstream file(fileName ? fileName : "");
  if (!file)
  {
    vtkErrorMacro(<< "Cannot write '" << (fileName ? fileName : "") << "'.");
    return false;
  }
  const vtkIdType rows = rowStart->GetNumberOfTuples() - 1;
  file << "%%MatrixMarket matrix coordinate real general\n"
       << "% MeshProjection: " << (matrix == MIXED_MASS ? "M_ts" : "M_tt") << ", "
       << TransferName(transfer) << "\n"
       << rows << " " << ncolumns << " " << values->GetNumberOfTuples() << "\n";
  file.precision(17);
  for (vtkIdType i = 0; i < rows; ++i)
  {
    for (vtkIdType p = rowStart->GetValue(i); p < rowStart->GetValue(i + 1); ++p)
    {
      file << i + 1 << " " << columns->GetValue(p) + 1 << " " << values->GetValue(p) << "\n";
    }
  }
  file.close();
  if (!file)
  {
    vtkErrorMacro(<< "Writing '" << fileName << "' failed.");
    return false;
  }
  return true;
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
  os << indent << "PointDataTarget: " << this->PointDataTarget << "\n";
  os << indent << "CellDataTarget: " << this->CellDataTarget << "\n";
  os << indent << "CellDataQuantity: " << (this->CellDataQuantity == EXTENSIVE ? "Extensive" : "Intensive") << "\n";
  os << indent << "MassMatrix: " << (this->MassMatrix == LUMPED_MASS ? "Lumped" : "Consistent") << "\n";
  os << indent << "PreserveBounds: " << (this->PreserveBounds ? "On" : "Off") << "\n";
  os << indent << "CacheOperator: " << (this->CacheOperator ? "On" : "Off") << "\n";
  os << indent << "OperatorReused: " << (this->OperatorReused ? "Yes" : "No") << "\n";
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
