// SPDX-License-Identifier: BSD-3-Clause
/*
 * The pipeline's side of the filter: ports, information, time, properties,
 * and RequestData as the list of the execution's stages. Each stage lives
 * in a room of its own (docs/design.md):
 *   Projection/  the stages of a projection (Source side, leaves, outputs)
 *   Adapter/     datasets seen as the kernel's meshes, the filter's threads
 *   Parallel/    the seam to the processes (Parts.h: serial by default)
 *   Kernel/      the VTK-free geometry, search and transfer
 */
#include "vtkMeshProjectionFilter.h"
#include "vtkMeshProjectionFilterInternals.h"

#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArraySelection.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedIntArray.h"
#include "vtkUnstructuredGrid.h"

#include "Adapter/SimplexMesh.h"
#include "Adapter/Threads.h"
#include "Parallel/Parts.h"
#include "Projection/ArraySelection.h"
#include "Projection/CellReconstruction.h"
#include "Projection/Composite.h"
#include "Projection/LeafProjection.h"
#include "Projection/MatrixExport.h"
#include "Projection/Messages.h"
#include "Projection/OperatorCache.h"
#include "Projection/Outputs.h"
#include "Projection/Settings.h"
#include "Projection/SourceSide.h"

#include <algorithm>
#include <cstdlib>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkMeshProjectionFilter);

//------------------------------------------------------------------------------
// The properties and mpvtk::Settings. A property and its field hold the same
// value (the static_asserts below): CellDataQuantity and MassMatrix are 0 or
// 1 (clamped), false or true.
template <typename Filter, typename Fields, typename Each>
void vtkMeshProjectionFilter::Internals::ForEachProperty(Filter& f, Fields& s, Each each)
{
  each(f.SearchMethod, s.SearchMethod);
  each(f.OutputIntersections, s.OutputIntersections);
  each(f.FillWithNaN, s.FillWithNaN);
  each(f.FillValue, s.FillValue);
  each(f.Extrapolation, s.Extrapolation);
  each(f.FringeThreshold, s.FringeThreshold);
  each(f.PointDataTarget, s.PointDataTarget);
  each(f.CellDataTarget, s.CellDataTarget);
  each(f.CellDataQuantity, s.Extensive);
  each(f.CellDataReconstruction, s.CellDataReconstruction);
  each(f.MassMatrix, s.Lumped);
  each(f.PreserveBounds, s.PreserveBounds);
  each(f.MaximumIterations, s.MaximumIterations);
  each(f.SurfaceReach, s.SurfaceReach);
  each(f.MaximumNormalAngle, s.MaximumNormalAngle);
  each(f.NormalOrientation, s.NormalOrientation);
  each(f.ConserveSourceIntegral, s.ConserveSourceIntegral);
  each(f.CacheOperator, s.CacheOperator);
  each(f.KeepMatrices, s.KeepMatrices);
  each(f.NumberOfThreads, s.NumberOfThreads);
  each(f.Renumbering, s.Renumbering);
  each(f.CurvedCellSubdivision, s.CurvedCellSubdivision);
  each(f.DensityArray, s.DensityArray);
  each(f.CategoricalMode, s.CategoricalMode);
  each(f.LabelFractions, s.LabelFractions);
  each(f.FillLabel, s.FillLabel);
}

mpvtk::Settings vtkMeshProjectionFilter::Internals::Read(const vtkMeshProjectionFilter& filter)
{
  mpvtk::Settings s;
  ForEachProperty(filter, s, [](const auto& property, auto& field) {
    field = static_cast<std::decay_t<decltype(field)>>(property);
  });
  const Internals& lists = *filter.Internal;
  s.TangentArrays = lists.TangentArrays.All();
  s.MassWeightedArrays = lists.MassWeightedArrays.All();
  s.CategoricalArrays.insert(
    lists.CategoricalArrays.All().begin(), lists.CategoricalArrays.All().end());
  return s;
}

void vtkMeshProjectionFilter::Internals::SetDefaults(vtkMeshProjectionFilter& filter)
{
  const mpvtk::Settings defaults;
  ForEachProperty(filter, defaults, [](auto& property, const auto& field) {
    property = static_cast<std::decay_t<decltype(property)>>(field);
  });
  // (The list properties, Internals' NameLists, start empty as a default mpvtk::Settings's.)
}

// The public constants are the values of Projection's own (Settings.h,
// Transfers.h, MatrixExport.h) and the kernel's, which Projection uses
// without seeing the public header: the casts here (ForEachProperty, GetMatrix)
// are exact.
namespace
{
using F = vtkMeshProjectionFilter;
/// A public constant and the internal value it stands for (two enumerations, compared as ints).
template <typename Public, typename Internal>
constexpr bool Same(Public constant, Internal value)
{
  return static_cast<int>(constant) == static_cast<int>(value);
}
static_assert(Same(F::ADVANCING_FRONT, mp::SearchMethod::AdvancingFront) &&
    Same(F::BRUTE_FORCE, mp::SearchMethod::BruteForce),
  "SearchMethods are mp::SearchMethod's values");
static_assert(Same(F::NO_EXTRAPOLATION, mp::ExtrapolationMode::None) &&
    Same(F::SMOOTH_EXTRAPOLATION, mp::ExtrapolationMode::Smooth) &&
    Same(F::NEAREST_EXTRAPOLATION, mp::ExtrapolationMode::Nearest),
  "Extrapolations are mp::ExtrapolationMode's values");
static_assert(Same(F::CONSTANT_RECONSTRUCTION, mp::Reconstruction::Constant) &&
    Same(F::LIMITED_RECONSTRUCTION, mp::Reconstruction::Limited) &&
    Same(F::UNLIMITED_RECONSTRUCTION, mp::Reconstruction::Unlimited),
  "Reconstructions are mp::Reconstruction's values");
static_assert(Same(F::CATEGORICAL_AUTOMATIC, mpvtk::CategoricalAutomatic) &&
    Same(F::CATEGORICAL_SELECTED, mpvtk::CategoricalSelected),
  "CategoricalModes are mpvtk::CategoricalModes");
static_assert(Same(F::TO_POINTS, mpvtk::ToPointsBit) && Same(F::TO_CELLS, mpvtk::ToCellsBit) &&
    Same(F::TO_POINTS_AND_CELLS, mpvtk::ToPointsBit | mpvtk::ToCellsBit),
  "Targets are mpvtk::TargetBits");
static_assert(
  Same(F::INTENSIVE, false) && Same(F::EXTENSIVE, true), "CellDataQuantity is Settings::Extensive");
static_assert(
  Same(F::CONSISTENT_MASS, false) && Same(F::LUMPED_MASS, true), "MassMatrix is Settings::Lumped");
static_assert(Same(F::SAME_ORIENTATION, mpvtk::SameOrientation) &&
    Same(F::OPPOSITE_ORIENTATION, mpvtk::OppositeOrientation) &&
    Same(F::ANY_ORIENTATION, mpvtk::AnyOrientation),
  "NormalOrientation is mp::MeshView::SurfaceOrientation");
static_assert(Same(F::AUTOMATIC_RENUMBERING, mpvtk::SimplexMesh::AUTOMATIC) &&
    Same(F::ALWAYS_RENUMBER, mpvtk::SimplexMesh::ALWAYS) &&
    Same(F::NEVER_RENUMBER, mpvtk::SimplexMesh::NEVER),
  "Renumbering is mpvtk::SimplexMesh::Ordering");
static_assert(Same(F::POINTS_TO_POINTS, mpvtk::PointsToPoints) &&
    Same(F::POINTS_TO_CELLS, mpvtk::PointsToCells) &&
    Same(F::CELLS_TO_CELLS, mpvtk::CellsToCells) && Same(F::CELLS_TO_POINTS, mpvtk::CellsToPoints),
  "Transfers are mpvtk::Transfer");
static_assert(Same(F::TARGET_MASS, mpvtk::Exported::TargetMass) &&
    Same(F::MIXED_MASS, mpvtk::Exported::MixedMass) &&
    Same(F::FRINGE_EXTENSION, mpvtk::Exported::FringeExtension) &&
    Same(F::EXTRAPOLATION, mpvtk::Exported::Extrapolation),
  "Matrices are mpvtk::Exported");
} // namespace

//------------------------------------------------------------------------------
vtkMeshProjectionFilter::vtkMeshProjectionFilter()
  : Internal(new Internals)
{
  Internals::SetDefaults(*this);
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
  // The test suite runs once more with every mesh renumbered (and once
  // with none): MESHPROJECTION_RENUMBERING=always|never sets the default.
  if (const char* forced = std::getenv("MESHPROJECTION_RENUMBERING"))
  {
    const std::string mode = forced;
    this->Renumbering = mode == "always" ? ALWAYS_RENUMBER
      : mode == "never"                  ? NEVER_RENUMBER
                                         : AUTOMATIC_RENUMBERING;
  }
  // A change of selection re-executes the filter; the arrays the filter
  // lists itself do not.
  for (int association = 0; association < 2; ++association)
  {
    this->Internal->Arrays.Selection(association)
      ->AddObserver(vtkCommand::ModifiedEvent, this, &vtkMeshProjectionFilter::SelectionModified);
  }
}

vtkMeshProjectionFilter::~vtkMeshProjectionFilter()
{
  delete this->Internal;
}

void vtkMeshProjectionFilter::SelectionModified()
{
  if (!this->Internal->Arrays.Listing())
  {
    this->Modified();
  }
}

void vtkMeshProjectionFilter::ListSource(vtkDataObject* data)
{
  vtkAlgorithm* producer =
    this->GetNumberOfInputConnections(1) > 0 ? this->GetInputAlgorithm(1, 0) : nullptr;
  this->Internal->Arrays.List(data, producer);
}

void vtkMeshProjectionFilter::AddTangentArray(const char* name)
{
  if (this->Internal->TangentArrays.Add(name))
  {
    this->Modified();
  }
}

void vtkMeshProjectionFilter::ClearTangentArrays()
{
  if (this->Internal->TangentArrays.Clear())
  {
    this->Modified();
  }
}

int vtkMeshProjectionFilter::GetNumberOfTangentArrays() const
{
  return this->Internal->TangentArrays.Count();
}

const char* vtkMeshProjectionFilter::GetTangentArray(int i) const
{
  return this->Internal->TangentArrays.Get(i);
}

vtkDataArraySelection* vtkMeshProjectionFilter::GetPointDataArraySelection()
{
  return this->Internal->Arrays.Selection(0);
}

vtkDataArraySelection* vtkMeshProjectionFilter::GetCellDataArraySelection()
{
  return this->Internal->Arrays.Selection(1);
}

void vtkMeshProjectionFilter::ClearPointDataArrayStatuses()
{
  this->Internal->Arrays.ClearStatuses(0);
}

void vtkMeshProjectionFilter::SetPointDataArrayStatus(const char* name, int status)
{
  this->Internal->Arrays.SetStatus(0, name, status);
}

void vtkMeshProjectionFilter::SetDensityArray(const char* name)
{
  // (None: the panel's entry for no density.)
  const std::string value = name && std::string(name) != "None" ? name : "";
  if (value != this->DensityArray)
  {
    this->DensityArray = value;
    this->Modified();
  }
}

void vtkMeshProjectionFilter::AddMassWeightedArray(const char* name)
{
  if (this->Internal->MassWeightedArrays.Add(name))
  {
    this->Modified();
  }
}

void vtkMeshProjectionFilter::ClearMassWeightedArrays()
{
  if (this->Internal->MassWeightedArrays.Clear())
  {
    this->Modified();
  }
}

int vtkMeshProjectionFilter::GetNumberOfMassWeightedArrays() const
{
  return this->Internal->MassWeightedArrays.Count();
}

const char* vtkMeshProjectionFilter::GetMassWeightedArray(int i) const
{
  return this->Internal->MassWeightedArrays.Get(i);
}

void vtkMeshProjectionFilter::ClearCellDataArrayStatuses()
{
  this->Internal->Arrays.ClearStatuses(1);
}

void vtkMeshProjectionFilter::SetCellDataArrayStatus(const char* name, int status)
{
  this->Internal->Arrays.SetStatus(1, name, status);
}

void vtkMeshProjectionFilter::AddCategoricalArray(const char* name)
{
  if (this->Internal->CategoricalArrays.Add(name))
  {
    this->Modified();
  }
}

void vtkMeshProjectionFilter::ClearCategoricalArrays()
{
  if (this->Internal->CategoricalArrays.Clear())
  {
    this->Modified();
  }
}

int vtkMeshProjectionFilter::GetNumberOfCategoricalArrays() const
{
  return this->Internal->CategoricalArrays.Count();
}

const char* vtkMeshProjectionFilter::GetCategoricalArray(int i) const
{
  return this->Internal->CategoricalArrays.Get(i);
}

vtkIdType vtkMeshProjectionFilter::GetOperatorMemory()
{
  return static_cast<vtkIdType>(this->Internal->Cache.MemoryBytes());
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
  // Any dataset, or a composite of datasets (multiblock, partitioned).
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
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
  // Port 0 has Input's type (RequestDataObject); the pieces have their own.
  info->Set(vtkDataObject::DATA_TYPE_NAME(),
    port == 0 ? "vtkDataObject" : (port == 1 ? "vtkPolyData" : "vtkUnstructuredGrid"));
  return 1;
}

int vtkMeshProjectionFilter::RequestDataObject(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Output 0 is of Input's type, as in vtkResampleWithDataSet.
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkInformation* info = outputVector->GetInformationObject(0);
  vtkDataObject* output = info->Get(vtkDataObject::DATA_OBJECT());
  if (input && (!output || !output->IsA(input->GetClassName())))
  {
    vtkSmartPointer<vtkDataObject> fresh;
    fresh.TakeReference(input->NewInstance());
    info->Set(vtkDataObject::DATA_OBJECT(), fresh);
  }
  for (int port = 1; port < 3; ++port)
  {
    vtkInformation* piecesInfo = outputVector->GetInformationObject(port);
    if (!piecesInfo->Get(vtkDataObject::DATA_OBJECT()))
    {
      vtkSmartPointer<vtkDataObject> pieces;
      if (port == 1)
      {
        pieces = vtkSmartPointer<vtkPolyData>::New();
      }
      else
      {
        pieces = vtkSmartPointer<vtkUnstructuredGrid>::New();
      }
      piecesInfo->Set(vtkDataObject::DATA_OBJECT(), pieces);
    }
  }
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
    this->ListSource(sourceInfo->Get(vtkDataObject::DATA_OBJECT()));
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
    // A structured Source whole, not the Input's extent (the pipeline's
    // default): a reader would give only the part inside that extent, and
    // an extent beyond the Source's is an error.
    sourceInfo->Remove(SDDP::UPDATE_EXTENT());
    if (sourceInfo->Has(SDDP::WHOLE_EXTENT()))
    {
      sourceInfo->Set(SDDP::UPDATE_EXTENT(), sourceInfo->Get(SDDP::WHOLE_EXTENT()), 6);
    }
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
void vtkMeshProjectionFilter::Internals::Publish(
  vtkMeshProjectionFilter& filter, const mpvtk::Statistics& stats, double seconds)
{
  filter.NumberOfIntersections = stats.Intersections;
  filter.NumberOfIntersectionTests = stats.IntersectionTests;
  filter.NumberOfLocatorQueries = stats.LocatorQueries;
  filter.CoveredMeasure = stats.CoveredMeasure;
  filter.NumberOfOperatorsBuilt = stats.OperatorsBuilt;
  filter.NumberOfRenumberedMeshes = std::max(stats.RenumberedMeshes, 0);
  filter.InputTime = stats.Input;
  filter.CheckTime = stats.Check;
  filter.RenumberTime = stats.Renumber;
  filter.NeighborsTime = stats.Neighbors;
  filter.LocatorTime = stats.Locator;
  filter.SearchTime = stats.Search;
  filter.AssemblyTime = stats.Assembly;
  filter.SolveTime = stats.Solve;
  filter.OutputTime = stats.Output;
  filter.ExecutionTime = seconds;
}

int vtkMeshProjectionFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Every core by default: VTK's sequential backend (Debian's default)
  // gives way to STDThread inside this scope; another backend chosen by the
  // application (TBB, OpenMP) is kept, with the filter's number of threads.
  vtkSMPTools::Config config;
  config.MaxNumberOfThreads = this->NumberOfThreads > 0
    ? this->NumberOfThreads
    : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (config.Backend == "Sequential" && config.MaxNumberOfThreads > 1)
  {
    config.Backend = "STDThread";
  }
  int result = 0;
  vtkSMPTools::LocalScope(config, [&]() {
    // Threads started once for the execution's loops (mpvtk::WorkerScope).
    mpvtk::WorkerScope workers(vtkSMPTools::GetEstimatedNumberOfThreads());
    result = this->Execute(inputVector, outputVector);
  });
  this->Internal->Executed.Modified();
  return result;
}

int vtkMeshProjectionFilter::Execute(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  mpvtk::StageClock clock;
  mpvtk::Statistics stats;
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  vtkPolyData* polygons = vtkPolyData::GetData(outputVector, 1);
  vtkUnstructuredGrid* polyhedra = vtkUnstructuredGrid::GetData(outputVector, 2);
  this->OperatorReused = false;
  Internals::Publish(*this, stats, 0.0); // no figures of an earlier execution while this one runs
  // The output is Input as it came, whatever happens next.
  mpvtk::PassInput(input, output, polygons, polyhedra);
  mpvtk::Verdict outcome;
  if (input && !vtkDataObject::GetData(inputVector[1], 0))
  {
    outcome = mpvtk::Verdict::Fail("No Source is connected (input port 1): nothing to project.");
  }
  else if (input)
  {
    // The seam: one process, unless vtkPMeshProjectionFilter installed its own.
    mpvtk::SerialParts alone;
    mpvtk::Parts& parts = this->Internal->Parts ? *this->Internal->Parts : alone;
    // The steps of one process alone turn their exceptions into failures
    // that all processes agree on (mpvtk::Guarded); one that gets here came
    // from a step with collectives inside: an error on one process, the
    // end of the run on several (Parts::Abandon: the others may wait in it).
    bool thrown = true; // until Project returns
    outcome = mpvtk::Guarded("The projection", [&]() {
      const mpvtk::Verdict projected =
        Internals::Project(*this, inputVector, outputVector, parts, clock, stats);
      thrown = false;
      return projected;
    });
    if (thrown)
    {
      parts.Abandon(outcome.Why);
      mpvtk::PassInput(input, output, polygons, polyhedra); // (what a leaf had written goes)
    }
  }
  switch (outcome.What)
  {
    case mpvtk::Outcome::Failed:
      vtkErrorMacro(<< outcome.Message());
      break;
    case mpvtk::Outcome::Stopped:
      mpvtk::PassInput(input, output, polygons, polyhedra);
      vtkWarningMacro("Aborted: the output is Input as it came.");
      break;
    case mpvtk::Outcome::Done:
      if (input)
      {
        stats.Output += clock.Lap();
        this->UpdateProgress(1.0);
      }
      break;
  }
  // (The execution's time only when it went through.)
  Internals::Publish(*this, stats, input && outcome.Ok() ? clock.Total() : 0.0);
  return 1;
}

namespace
{
/// Whether an input advertises several time steps (operators then pay to keep).
bool InputsVaryInTime(vtkInformationVector** inputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  bool varying = false;
  for (int port = 0; port < 2; ++port)
  {
    vtkInformation* info = inputVector[port]->GetInformationObject(0);
    varying =
      varying || (info && info->Has(SDDP::TIME_STEPS()) && info->Length(SDDP::TIME_STEPS()) > 1);
  }
  return varying;
}

/// Names the leaf's block in its pieces (a composite Input's pieces are appended).
void MarkPiecesBlock(vtkDataObject* pieces, unsigned int flatIndex)
{
  vtkDataSet* data = vtkDataSet::SafeDownCast(pieces);
  vtkNew<vtkUnsignedIntArray> block;
  block->SetName("TargetBlock");
  block->SetNumberOfValues(data->GetNumberOfCells());
  block->Fill(flatIndex);
  data->GetCellData()->AddArray(block);
}
} // namespace

mpvtk::Verdict vtkMeshProjectionFilter::Internals::Project(vtkMeshProjectionFilter& filter,
  vtkInformationVector** inputVector, vtkInformationVector* outputVector, mpvtk::Parts& parts,
  mpvtk::StageClock& clock, mpvtk::Statistics& stats)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkDataObject* sourceObject = vtkDataObject::GetData(inputVector[1], 0);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  Internals& in = *filter.Internal;
  const mpvtk::Settings settings = Read(filter);
  mpvtk::Messages say(&filter, in.Warned);
  mpvtk::Progress progress(&filter);

  // 1. Source as one mesh, then its fields (the arrays listed first: the
  // selection says which of this process's piece are labels).
  filter.ListSource(sourceObject);
  vtkDataArraySelection* const selections[2] = { in.Arrays.Selection(0), in.Arrays.Selection(1) };
  mpvtk::SourceSide source;
  mpvtk::Verdict verdict =
    mpvtk::PrepareSourceMesh(sourceObject, input, settings, selections, parts, say, stats, source);
  if (!verdict.Ok())
  {
    return verdict;
  }
  mpvtk::GatherSourceFields(
    source.Data, source.Mesh, selections, settings, say, parts, source.Fields);
  mpvtk::ReconstructCellFields(
    settings, source.Mesh, source.Print, source.Fields[mpvtk::CellArrays], in.Cache.Reconstruction);
  if (!source.AnyTransfer(settings))
  {
    say.Warn("Source has no arrays to project (or none selected): only vtkValidPointMask and "
             "CoveredFraction are computed.");
  }
  source.TimeVarying = InputsVaryInTime(inputVector);
  stats.Input += clock.Lap();
  // A stop (the abort flag) is local: on several processes all stop
  // together, at the points where they agree, or none waits for the others.
  bool go = progress(0.05);
  parts.Agree(mpvtk::Verdict(), &go);
  if (!go)
  {
    return mpvtk::Verdict::Stop();
  }

  // 2. Each dataset of Input: its own projection (one system per leaf).
  const mpvtk::InputLeaves leaves = mpvtk::LeavesOf(input, output, parts, say);
  in.Cache.KeepOnly(leaves.FlatIndices(), settings);
  const mpvtk::ExecutionShare share{ settings, parts, say, clock, source };
  const bool composite = vtkCompositeDataSet::SafeDownCast(input) != nullptr;
  const size_t n = leaves.Leaves.size();
  std::vector<vtkSmartPointer<vtkDataObject>> pieces;
  std::vector<std::string> skipped;
  int projected = 0;
  for (size_t i = 0; i < n; ++i)
  {
    const mpvtk::InputLeaf& leaf = leaves.Leaves[i];
    if (composite && leaf.EmptyEverywhere)
    {
      vtkDebugWithObjectMacro(&filter, << leaf.Name << " is empty: skipped.");
      continue;
    }
    const mpvtk::LeafJob job{ leaf.Target, leaf.Output,
      leaf.Name.empty() ? std::string("Input") : "Input " + leaf.Name,
      { &progress, 0.05 + 0.9 * static_cast<double>(i) / n, 0.9 / n }, i + 1 == n };
    mpvtk::LeafResult result = mpvtk::ProjectLeaf(share, job, in.Cache.Leaves[leaf.FlatIndex]);
    stats += result.Stats;
    if (result.Outcome.What == mpvtk::Outcome::Stopped)
    {
      return result.Outcome;
    }
    if (result.Outcome.What == mpvtk::Outcome::Failed)
    {
      leaf.Output->ShallowCopy(leaf.Target);
      in.Cache.Leaves.erase(leaf.FlatIndex);
      if (!composite)
      {
        return result.Outcome;
      }
      skipped.push_back(result.Outcome.Message()); // names the block
      continue;
    }
    ++projected;
    if (result.Pieces)
    {
      if (composite)
      {
        MarkPiecesBlock(result.Pieces, leaf.FlatIndex);
      }
      pieces.push_back(result.Pieces);
    }
  }
  ReportSkipped(skipped, n, projected, say);

  // 3. Optionally, the intersection pieces of every leaf.
  mpvtk::WritePieces(
    pieces, vtkPolyData::GetData(outputVector, 1), vtkUnstructuredGrid::GetData(outputVector, 2));
  filter.OperatorReused = projected > 0 && stats.OperatorsBuilt == 0;
  return mpvtk::Verdict();
}

void vtkMeshProjectionFilter::Internals::ReportSkipped(
  const std::vector<std::string>& skipped, size_t leaves, int projected, mpvtk::Messages& say)
{
  if (skipped.empty())
  {
    return;
  }
  std::ostringstream text;
  text << skipped.size() << " of " << leaves
       << " Input blocks could not be projected and are passed through:";
  for (const std::string& s : skipped)
  {
    text << "\n  " << s;
  }
  if (projected == 0)
  {
    say.Error(text.str());
  }
  else
  {
    say.WarnOnce("blocks/" + text.str(), text.str()); // once, not at every step
  }
}

//------------------------------------------------------------------------------
vtkIdType vtkMeshProjectionFilter::GetMatrix(int transfer, int matrix, vtkIdTypeArray* rowStart,
  vtkIdTypeArray* columns, vtkDoubleArray* values)
{
  const bool known = transfer >= 0 && transfer <= 3;
  if (matrix < TARGET_MASS || matrix > EXTRAPOLATION)
  {
    vtkErrorMacro(<< "No matrix number " << matrix
                  << ": TARGET_MASS (0), MIXED_MASS (1), "
                     "FRINGE_EXTENSION (2) or EXTRAPOLATION (3).");
    return -1;
  }
  const mpvtk::Transfer t = known ? static_cast<mpvtk::Transfer>(transfer) : mpvtk::PointsToPoints;
  // A getter: it reads what the last execution kept and never executes
  // (on several processes an execution is collective). A filter changed
  // since (a property, an input's data) would give another execution's
  // matrices: the caller updates first.
  const vtkMTimeType executed = this->Internal->Executed.GetMTime();
  bool changed = executed == 0 || this->GetMTime() > executed;
  for (int port = 0; port < 2; ++port)
  {
    vtkDataObject* in =
      this->GetNumberOfInputConnections(port) ? this->GetInputDataObject(port, 0) : nullptr;
    changed = changed || (in && in->GetMTime() > executed);
  }
  if (changed)
  {
    vtkErrorMacro(<< "GetMatrix reads the operators of the last execution, and the filter "
                  << (executed == 0 ? "has not executed"
                                    : "or its inputs changed since it executed")
                  << ": set KeepMatrices on and call Update() first.");
    return -1;
  }
  const mpvtk::OperatorCache& cache = this->Internal->Cache;
  if (!rowStart || !columns || !values || !known || !cache.FirstOperator(t))
  {
    vtkErrorMacro(<< "No operator of " << (known ? mpvtk::TransferName(t) : "that number")
                  << " is kept: execute the filter with CacheOperator and KeepMatrices on and "
                     "that transfer in use (a one-off execution keeps no operator).");
    return -1;
  }
  if (matrix == MIXED_MASS && cache.FirstOperator(t)->GetSourceSpace() == mp::SpaceType::DP1)
  {
    vtkErrorMacro(<< "The mixed matrix of " << mpvtk::TransferName(t)
                  << " reads the reconstructed cell data (values at the corners of the Source's "
                     "simplices), not Source's cells: export it with CellDataReconstruction "
                     "Constant.");
    return -1;
  }
  const mp::MortarOperator& op = *cache.FirstOperator(t);
  if (matrix == FRINGE_EXTENSION && mpvtk::FringeReachesHalo(op))
  {
    vtkErrorMacro(<< "The fringe's extension of " << mpvtk::TransferName(t)
                  << " on this process reaches points of the other processes (its stencils are "
                     "the serial ones), which this process's numbering does not hold: export it "
                     "from one process.");
    return -1;
  }
  return mpvtk::ExportMatrix(
    *cache.FirstLeaf(t), t, static_cast<mpvtk::Exported>(matrix), rowStart, columns, values);
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
  const std::string title = std::string(matrix == MIXED_MASS ? "M_ts"
                                : matrix == FRINGE_EXTENSION ? "P"
                                : matrix == EXTRAPOLATION    ? "E"
                                                             : "M_tt") +
    ", " + mpvtk::TransferName(static_cast<mpvtk::Transfer>(transfer));
  const std::string error = mpvtk::WriteMatrixMarketFile(
    fileName ? fileName : "", title, ncolumns, rowStart, columns, values);
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMeshProjectionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "SearchMethod: " << (this->SearchMethod == BRUTE_FORCE ? "BruteForce" : "AdvancingFront")
     << "\n";
  os << indent << "OutputIntersections: " << (this->OutputIntersections ? "On" : "Off") << "\n";
  os << indent << "FillWithNaN: " << (this->FillWithNaN ? "On" : "Off") << "\n";
  os << indent << "FillValue: " << this->FillValue << "\n";
  os << indent << "Extrapolation: " << this->Extrapolation << "\n";
  os << indent << "FringeThreshold: " << this->FringeThreshold << "\n";
  os << indent << "PointDataTarget: " << this->PointDataTarget << "\n";
  os << indent << "CellDataTarget: " << this->CellDataTarget << "\n";
  os << indent
     << "CellDataQuantity: " << (this->CellDataQuantity == EXTENSIVE ? "Extensive" : "Intensive")
     << "\n";
  os << indent << "CellDataReconstruction: " << this->CellDataReconstruction << "\n";
  os << indent << "CategoricalMode: " << this->CategoricalMode << "\n";
  os << indent << "CategoricalArrays:";
  for (const std::string& name : this->Internal->CategoricalArrays.All())
  {
    os << " " << name;
  }
  os << "\n";
  os << indent << "LabelFractions: " << this->LabelFractions << "\n";
  os << indent << "FillLabel: " << this->FillLabel << "\n";
  os << indent << "MassMatrix: " << (this->MassMatrix == LUMPED_MASS ? "Lumped" : "Consistent")
     << "\n";
  os << indent << "PreserveBounds: " << (this->PreserveBounds ? "On" : "Off") << "\n";
  os << indent << "MaximumIterations: " << this->MaximumIterations << "\n";
  os << indent << "SurfaceReach: " << this->SurfaceReach << "\n";
  os << indent << "CurvedCellSubdivision: " << this->CurvedCellSubdivision << "\n";
  os << indent << "ConserveSourceIntegral: " << (this->ConserveSourceIntegral ? "On" : "Off")
     << "\n";
  os << indent << "MaximumNormalAngle: " << this->MaximumNormalAngle << "\n";
  os << indent << "NormalOrientation: " << this->NormalOrientation << "\n";
  os << indent << "CacheOperator: " << (this->CacheOperator ? "On" : "Off") << "\n";
  os << indent << "KeepMatrices: " << (this->KeepMatrices ? "On" : "Off") << "\n";
  os << indent << "DensityArray: " << this->DensityArray << "\n";
  os << indent << "MassWeightedArrays:";
  for (const std::string& name : this->Internal->MassWeightedArrays.All())
  {
    os << " " << name;
  }
  os << "\n";
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
