// SPDX-License-Identifier: BSD-3-Clause
// Cell data and the transfers a user chooses, in 2D and 3D on the sample
// meshes: P0 -> P0 intensive (exact on constants, conservative) and
// extensive (totals kept), P1 -> P0 and P0 -> P1, lumped and bounded
// transfers, array selection, operators kept and reused (hits and misses),
// the matrices read out and written, and an aborted run.
#include "MeshProjectionTestUtilities.h"
#include "vtkMeshProjectionFilter.h"

#include "vtkCallbackCommand.h"
#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkCommand.h"
#include "vtkDataArraySelection.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"
#include "vtkTestErrorObserver.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace
{
using mptest::CellMeasure;

double Centroid(vtkUnstructuredGrid* grid, vtkIdType c, int axis)
{
  const vtkIdType* ids;
  vtkIdType n;
  grid->GetCells()->GetCellAtId(c, n, ids);
  double sum = 0;
  for (vtkIdType k = 0; k < n; ++k)
  {
    sum += grid->GetPoint(ids[k])[axis] / n;
  }
  return sum;
}

vtkSmartPointer<vtkDoubleArray> CellArray(
  vtkUnstructuredGrid* grid, const char* name, const std::function<double(vtkIdType)>& f)
{
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfValues(grid->GetNumberOfCells());
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    a->SetValue(c, f(c));
  }
  return a;
}

/// Sum over cells of measure x value (an intensive cell array's integral).
double CellIntegral(vtkUnstructuredGrid* grid, vtkDataArray* u)
{
  double sum = 0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const vtkIdType* ids;
    vtkIdType n;
    sum += CellMeasure(grid, c, &ids, &n) * u->GetComponent(c, 0);
  }
  return sum;
}

double Sum(vtkDataArray* u)
{
  double sum = 0;
  for (vtkIdType i = 0; i < u->GetNumberOfTuples(); ++i)
  {
    sum += u->GetComponent(i, 0);
  }
  return sum;
}

/**
 * One sample pair and the filter run on it, shared by the cases of CheckFields: they
 * run in order on the one filter, each from the properties and kept operators the
 * cases before it left. Source has the cell fields One (a constant), Density (a
 * step) and Mass (density x measure, totals) in place of its own cell data, and
 * the point field Step (for the bounds).
 */
struct FieldsRun
{
  FieldsRun(const char* targetFile, const char* sourceFile);
  const char* TargetFile;
  bool Is3D;
  vtkSmartPointer<vtkUnstructuredGrid> Target;
  vtkSmartPointer<vtkUnstructuredGrid> Source;
  vtkNew<vtkDoubleArray> Step;
  vtkNew<vtkMeshProjectionFilter> Filter;
  vtkNew<vtkTest::ErrorObserver> Observer;
  vtkUnstructuredGrid* Out = nullptr; // the filter's output, from CheckCellTransfers on
};

FieldsRun::FieldsRun(const char* targetFile, const char* sourceFile)
  : TargetFile(targetFile)
  , Is3D(std::string(targetFile).find("3d") != std::string::npos)
  , Target(mptest::ReadSample(targetFile))
  , Source(mptest::ReadSample(sourceFile))
{
  vtkUnstructuredGrid* source = this->Source;
  vtkDoubleArray* step = this->Step;
  source->GetCellData()->Initialize();
  // Cell fields: a constant, a step (a density) and totals (mass = density x measure).
  source->GetCellData()->AddArray(CellArray(source, "One", [](vtkIdType) { return 1.0; }));
  auto density = [&](vtkIdType c) { return Centroid(source, c, 0) > 0.8 ? 3.0 : 1.0; };
  source->GetCellData()->AddArray(CellArray(source, "Density", density));
  source->GetCellData()->AddArray(CellArray(source, "Mass", [&](vtkIdType c) {
    const vtkIdType* ids;
    vtkIdType n;
    return density(c) * CellMeasure(source, c, &ids, &n);
  }));
  // A point step for the bounds.
  step->SetName("Step");
  step->SetNumberOfValues(source->GetNumberOfPoints());
  for (vtkIdType p = 0; p < source->GetNumberOfPoints(); ++p)
  {
    step->SetValue(p, source->GetPoint(p)[0] > 0.8 ? 2.0 : -1.0);
  }
  source->GetPointData()->AddArray(step);
}

/// The sample pairs cover the same domain; cell -> cell (intensive), point -> cell and
/// cell -> point on the first run (all four operators built).
bool CheckCellTransfers(FieldsRun& run)
{
  int failures = 0;
  vtkUnstructuredGrid* target = run.Target;
  vtkUnstructuredGrid* source = run.Source;
  const char* targetFile = run.TargetFile;
  const bool is3D = run.Is3D;
  vtkMeshProjectionFilter* filter = run.Filter;
  vtkTest::ErrorObserver* observer = run.Observer;
  const double sourceMeasure = mptest::Measure(source);
  const double targetMeasure = mptest::Measure(target);
  // The sample pairs cover the same domain.
  MP_CHECK(std::fabs(sourceMeasure - targetMeasure) < 1e-12 * sourceMeasure);

  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->SetInputData(target);
  filter->SetSourceData(source);
  filter->SetPointDataTarget(vtkMeshProjectionFilter::TO_POINTS_AND_CELLS);
  filter->SetCellDataTarget(vtkMeshProjectionFilter::TO_POINTS_AND_CELLS);
  filter->Update();
  MP_CHECK(!observer->GetError() && !observer->GetWarning());
  MP_CHECK(filter->GetNumberOfOperatorsBuilt() == 4 && !filter->GetOperatorReused());
  vtkUnstructuredGrid* out = filter->GetUnstructuredGridOutput();
  vtkCellData* cd = out->GetCellData();
  vtkPointData* pd = out->GetPointData();

  // Cell -> cell, intensive: constants exact, the integral kept.
  vtkDataArray* one = cd->GetArray("One");
  MP_CHECK(
    one && std::fabs(one->GetRange()[0] - 1) < 1e-13 && std::fabs(one->GetRange()[1] - 1) < 1e-13);
  vtkDataArray* dens = cd->GetArray("Density");
  const double sourceDensity = CellIntegral(source, source->GetCellData()->GetArray("Density"));
  MP_CHECK(dens && std::fabs(CellIntegral(out, dens) - sourceDensity) < 1e-13 * sourceDensity);
  MP_CHECK(dens && dens->GetRange()[0] >= 1 - 1e-13 && dens->GetRange()[1] <= 3 + 1e-13);
  MP_CHECK(
    cd->GetArray("vtkValidCellMask") && cd->GetArray("vtkValidCellMask")->GetRange()[0] == 1);
  // Point -> cell: a linear field's cell means are the values at the centroids.
  vtkDataArray* linearCells = cd->GetArray("Linear (from points)")
    ? cd->GetArray("Linear (from points)")
    : cd->GetArray("Linear");
  double worst = 0;
  for (vtkIdType c = 0; linearCells && c < out->GetNumberOfCells(); ++c)
  {
    const double x = Centroid(out, c, 0), y = Centroid(out, c, 1), z = Centroid(out, c, 2);
    const double exact = is3D ? 1 + 2 * x - 3 * y + 0.5 * z : 1 + 2 * x - 3 * y;
    worst = std::max(worst, std::fabs(linearCells->GetComponent(c, 0) - exact));
  }
  std::cout << targetFile << ": point -> cell linear error " << worst << "\n";
  MP_CHECK(linearCells && worst < 1e-12);
  // Cell -> point: constants exact, the integral kept.
  vtkDataArray* onePoints = pd->GetArray("One");
  MP_CHECK(onePoints && std::fabs(onePoints->GetRange()[0] - 1) < 1e-12 &&
    std::fabs(onePoints->GetRange()[1] - 1) < 1e-12);
  vtkDataArray* densPoints = pd->GetArray("Density");
  MP_CHECK(densPoints &&
    std::fabs(mptest::Integral(out, densPoints) - sourceDensity) < 1e-12 * sourceDensity);
  run.Out = out;
  return failures == 0;
}

/// Extensive: totals kept (the meshes cover the same domain).
bool CheckExtensive(FieldsRun& run)
{
  int failures = 0;
  vtkMeshProjectionFilter* filter = run.Filter;
  vtkUnstructuredGrid* source = run.Source;
  const char* targetFile = run.TargetFile;
  filter->SetCellDataQuantity(vtkMeshProjectionFilter::EXTENSIVE);
  filter->Update();
  // The first execution was a one-off (right-hand sides summed in the
  // search, M_ts not formed); the second on the same meshes assembles the
  // operators, and later ones reuse them.
  MP_CHECK(!filter->GetOperatorReused() && filter->GetNumberOfOperatorsBuilt() == 4);
  vtkDataArray* mass = filter->GetUnstructuredGridOutput()->GetCellData()->GetArray("Mass");
  const double totalMass = Sum(source->GetCellData()->GetArray("Mass"));
  std::cout << targetFile << ": extensive total " << (mass ? Sum(mass) : -1) << " vs " << totalMass
            << "\n";
  MP_CHECK(mass && std::fabs(Sum(mass) - totalMass) < 1e-12 * totalMass);
  // Its cell -> point transfer is the density.
  vtkDataArray* massDensity = filter->GetUnstructuredGridOutput()->GetPointData()->GetArray("Mass");
  MP_CHECK(massDensity &&
    std::fabs(mptest::Integral(filter->GetUnstructuredGridOutput(), massDensity) - totalMass) <
      1e-12 * totalMass);
  filter->SetCellDataQuantity(vtkMeshProjectionFilter::INTENSIVE);
  return failures == 0;
}

/// The matrices: M_tt u_t = M_ts u_s for the projected point field.
bool CheckMatrices(FieldsRun& run)
{
  int failures = 0;
  vtkMeshProjectionFilter* filter = run.Filter;
  vtkUnstructuredGrid* target = run.Target;
  vtkUnstructuredGrid* source = run.Source;
  const char* targetFile = run.TargetFile;
  vtkTest::ErrorObserver* observer = run.Observer;
  filter->SetPointDataTarget(vtkMeshProjectionFilter::TO_POINTS);
  filter->SetCellDataTarget(vtkMeshProjectionFilter::TO_CELLS);
  filter->Update();
  MP_CHECK(filter->GetOperatorReused());
  vtkNew<vtkIdTypeArray> rowStart, columns, rowStartS, columnsS;
  vtkNew<vtkDoubleArray> values, valuesS;
  const vtkIdType nt = filter->GetMatrix(vtkMeshProjectionFilter::POINTS_TO_POINTS,
    vtkMeshProjectionFilter::TARGET_MASS, rowStart, columns, values);
  const vtkIdType ns = filter->GetMatrix(vtkMeshProjectionFilter::POINTS_TO_POINTS,
    vtkMeshProjectionFilter::MIXED_MASS, rowStartS, columnsS, valuesS);
  MP_CHECK(nt == target->GetNumberOfPoints() && ns == source->GetNumberOfPoints());
  vtkDataArray* smooth = filter->GetUnstructuredGridOutput()->GetPointData()->GetArray("Smooth");
  vtkDataArray* smoothS = source->GetPointData()->GetArray("Smooth");
  double residual = 0, scale = 0;
  for (vtkIdType i = 0; nt > 0 && ns > 0 && i < nt; ++i)
  {
    double a = 0, b = 0;
    for (vtkIdType p = rowStart->GetValue(i); p < rowStart->GetValue(i + 1); ++p)
    {
      a += values->GetValue(p) * smooth->GetComponent(columns->GetValue(p), 0);
    }
    for (vtkIdType p = rowStartS->GetValue(i); p < rowStartS->GetValue(i + 1); ++p)
    {
      b += valuesS->GetValue(p) * smoothS->GetComponent(columnsS->GetValue(p), 0);
    }
    residual = std::max(residual, std::fabs(a - b));
    scale = std::max(scale, std::fabs(b));
  }
  MP_CHECK(residual < 1e-12 * scale);
  // Matrix Market: the header and the entry count.
  const std::string mtx = std::string(targetFile) + ".mtx";
  MP_CHECK(filter->WriteMatrixMarket(
    mtx.c_str(), vtkMeshProjectionFilter::POINTS_TO_POINTS, vtkMeshProjectionFilter::MIXED_MASS));
  {
    std::ifstream in(mtx);
    std::string header, comment;
    std::getline(in, header);
    std::getline(in, comment);
    vtkIdType r = 0, c = 0, nnz = 0;
    in >> r >> c >> nnz;
    MP_CHECK(header == "%%MatrixMarket matrix coordinate real general");
    MP_CHECK(r == nt && c == ns && nnz == valuesS->GetNumberOfTuples());
  }
  std::remove(mtx.c_str());
  // An operator not in use is not kept: an error and -1.
  MP_CHECK(filter->GetMatrix(
             vtkMeshProjectionFilter::CELLS_TO_POINTS, 0, rowStart, columns, values) == -1);
  MP_CHECK(observer->GetError());
  observer->Clear();
  // GetMatrix never executes the filter: it refuses before an execution,
  // after a one-off one (which keeps nothing) and after a change; with
  // KeepMatrices and an Update it gives the matrix.
  {
    using F = vtkMeshProjectionFilter;
    vtkNew<F> asked;
    vtkNew<vtkTest::ErrorObserver> said;
    asked->AddObserver(vtkCommand::ErrorEvent, said);
    asked->SetInputData(target);
    asked->SetSourceData(source);
    auto matrix = [&]() {
      return asked->GetMatrix(F::POINTS_TO_POINTS, F::TARGET_MASS, rowStart, columns, values);
    };
    auto refused = [&](const char* why) {
      const bool is = said->GetError() && said->GetErrorMessage().find(why) != std::string::npos;
      said->Clear();
      return is;
    };
    MP_CHECK(matrix() == -1 && refused("has not executed"));
    asked->Update();
    const vtkMTimeType executed = asked->GetOutputDataObject(0)->GetMTime();
    MP_CHECK(matrix() == -1 && refused("is kept")); // a one-off execution keeps nothing
    MP_CHECK(
      asked->GetOutputDataObject(0)->GetMTime() == executed); // and GetMatrix did not execute
    asked->SetKeepMatrices(true);
    MP_CHECK(matrix() == -1 && refused("changed since"));
    asked->Update();
    MP_CHECK(matrix() == nt && !said->GetError() && rowStart->GetNumberOfTuples() == nt + 1);
    asked->SetFillValue(7);
    MP_CHECK(matrix() == -1 && refused("changed since"));
  }
  return failures == 0;
}

/// Array selection: disabled arrays are not projected, the others are.
bool CheckArraySelection(FieldsRun& run)
{
  int failures = 0;
  vtkMeshProjectionFilter* filter = run.Filter;
  filter->GetPointDataArraySelection()->DisableArray("Smooth");
  filter->GetCellDataArraySelection()->DisableArray("Mass");
  filter->Update();
  MP_CHECK(!filter->GetUnstructuredGridOutput()->GetPointData()->GetArray("Smooth"));
  MP_CHECK(filter->GetUnstructuredGridOutput()->GetPointData()->GetArray("Linear"));
  MP_CHECK(!filter->GetUnstructuredGridOutput()->GetCellData()->GetArray("Mass"));
  MP_CHECK(filter->GetUnstructuredGridOutput()->GetCellData()->GetArray("Density"));
  MP_CHECK(filter->GetOperatorReused());
  filter->GetPointDataArraySelection()->EnableArray("Smooth");
  filter->GetCellDataArraySelection()->EnableArray("Mass");
  return failures == 0;
}

/// Lumped: within the source's range, conservative, constants exact.
bool CheckLumped(FieldsRun& run)
{
  int failures = 0;
  vtkMeshProjectionFilter* filter = run.Filter;
  vtkUnstructuredGrid* source = run.Source;
  vtkDoubleArray* step = run.Step;
  filter->SetMassMatrix(vtkMeshProjectionFilter::LUMPED_MASS);
  filter->Update();
  MP_CHECK(filter->GetOperatorReused());
  vtkDataArray* lumpedStep = filter->GetUnstructuredGridOutput()->GetPointData()->GetArray("Step");
  MP_CHECK(lumpedStep && lumpedStep->GetRange()[0] >= -1 - 1e-14 &&
    lumpedStep->GetRange()[1] <= 2 + 1e-14);
  const double stepIntegral = mptest::Integral(source, step);
  MP_CHECK(lumpedStep &&
    std::fabs(mptest::Integral(filter->GetUnstructuredGridOutput(), lumpedStep) - stepIntegral) <
      1e-13 * std::fabs(stepIntegral) + 1e-14);
  filter->SetMassMatrix(vtkMeshProjectionFilter::CONSISTENT_MASS);
  return failures == 0;
}

/// Bounds: the consistent projection of a step overshoots; with bounds it
/// does not, the integral stays, and linear fields stay exact.
bool CheckBounds(FieldsRun& run)
{
  int failures = 0;
  vtkMeshProjectionFilter* filter = run.Filter;
  vtkUnstructuredGrid* source = run.Source;
  const char* targetFile = run.TargetFile;
  const bool is3D = run.Is3D;
  vtkUnstructuredGrid* out = run.Out;
  const double stepIntegral = mptest::Integral(source, run.Step);
  double worst = 0;
  filter->Update();
  vtkDataArray* consistent = filter->GetUnstructuredGridOutput()->GetPointData()->GetArray("Step");
  const double overshoot = std::max(consistent->GetRange()[1] - 2, -1 - consistent->GetRange()[0]);
  filter->SetPreserveBounds(true);
  filter->Update();
  vtkDataArray* bounded = filter->GetUnstructuredGridOutput()->GetPointData()->GetArray("Step");
  const double boundedIntegral = mptest::Integral(filter->GetUnstructuredGridOutput(), bounded);
  std::cout << targetFile << ": step overshoot " << overshoot << " consistent, range ["
            << bounded->GetRange()[0] << ", " << bounded->GetRange()[1]
            << "] bounded, integral error " << std::fabs(boundedIntegral - stepIntegral) << "\n";
  MP_CHECK(overshoot > 0.01);
  MP_CHECK(bounded->GetRange()[0] >= -1 - 1e-13 && bounded->GetRange()[1] <= 2 + 1e-13);
  MP_CHECK(std::fabs(boundedIntegral - stepIntegral) < 1e-13 * std::fabs(stepIntegral) + 1e-14);
  vtkDataArray* linear = filter->GetUnstructuredGridOutput()->GetPointData()->GetArray("Linear");
  worst = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const double* x = filter->GetUnstructuredGridOutput()->GetPoint(i);
    const double exact = is3D ? 1 + 2 * x[0] - 3 * x[1] + 0.5 * x[2] : 1 + 2 * x[0] - 3 * x[1];
    worst = std::max(worst, std::fabs(linear->GetComponent(i, 0) - exact));
  }
  MP_CHECK(worst < 1e-12);
  filter->SetPreserveBounds(false);
  return failures == 0;
}

/// Reuse: a Source with the same geometry in new arrays is a hit (and a
/// new field), moved points a miss; with the cache off nothing is kept.
bool CheckReuse(FieldsRun& run)
{
  int failures = 0;
  vtkMeshProjectionFilter* filter = run.Filter;
  vtkUnstructuredGrid* target = run.Target;
  vtkUnstructuredGrid* source = run.Source;
  const char* targetFile = run.TargetFile;
  double worst = 0;
  vtkNew<vtkUnstructuredGrid> copy;
  copy->DeepCopy(source);
  filter->SetSourceData(copy);
  filter->Update();
  MP_CHECK(filter->GetOperatorReused() && filter->GetNumberOfOperatorsBuilt() == 0);
  MP_CHECK(filter->GetOperatorMemory() > 0);
  vtkNew<vtkDoubleArray> reused; // the next run replaces the output's arrays
  reused->DeepCopy(filter->GetUnstructuredGridOutput()->GetPointData()->GetArray("Smooth"));
  vtkNew<vtkUnstructuredGrid> moved;
  moved->DeepCopy(source);
  double x[3];
  moved->GetPoint(5, x);
  x[0] += 1e-9;
  moved->GetPoints()->SetPoint(5, x);
  filter->SetSourceData(moved);
  filter->Update();
  MP_CHECK(!filter->GetOperatorReused() && filter->GetNumberOfOperatorsBuilt() == 2);
  vtkNew<vtkMeshProjectionFilter> fresh;
  fresh->SetCacheOperator(false);
  fresh->SetInputData(target);
  fresh->SetSourceData(source);
  fresh->Update();
  MP_CHECK(fresh->GetOperatorMemory() == 0 && !fresh->GetOperatorReused());
  vtkDataArray* single = fresh->GetUnstructuredGridOutput()->GetPointData()->GetArray("Smooth");
  worst = 0;
  for (vtkIdType i = 0; single && i < single->GetNumberOfTuples(); ++i)
  {
    worst = std::max(worst, std::fabs(reused->GetComponent(i, 0) - single->GetComponent(i, 0)));
  }
  std::cout << targetFile << ": reused (warm start) vs single-use " << worst << "\n";
  MP_CHECK(single && reused->GetNumberOfTuples() == single->GetNumberOfTuples() && worst < 1e-12);
  return failures == 0;
}

/// Aborting from a progress observer, and the progress a whole run reports.
bool CheckAbort(FieldsRun& run)
{
  int failures = 0;
  vtkUnstructuredGrid* target = run.Target;
  vtkUnstructuredGrid* source = run.Source;
  // A run watched by a progress observer that stops it once the progress
  // is in (from, to): the progress it saw, and whether it said "Aborted".
  struct Watch
  {
    vtkMeshProjectionFilter* Filter;
    std::vector<double> Seen;
    double From, To;
  };
  auto watchedRun = [&](double from, double to, Watch& watch) {
    vtkSmartPointer<vtkMeshProjectionFilter> filter =
      vtkSmartPointer<vtkMeshProjectionFilter>::New();
    vtkNew<vtkTest::ErrorObserver> warnings;
    filter->AddObserver(vtkCommand::WarningEvent, warnings);
    filter->SetInputData(target);
    filter->SetSourceData(source);
    watch = Watch{ filter, {}, from, to };
    vtkNew<vtkCallbackCommand> onProgress;
    onProgress->SetClientData(&watch);
    onProgress->SetCallback([](vtkObject*, unsigned long, void* data, void* amount) {
      Watch* w = static_cast<Watch*>(data);
      const double f = *static_cast<double*>(amount);
      w->Seen.push_back(f);
      if (f > w->From && f < w->To)
      {
        w->Filter->SetAbortExecute(1);
      }
    });
    filter->AddObserver(vtkCommand::ProgressEvent, onProgress);
    filter->Update();
    const bool said =
      warnings->GetWarning() && warnings->GetWarningMessage().find("Aborted") != std::string::npos;
    return std::make_pair(filter, said);
  };
  // Abort from a progress observer: Input as it came, a warning.
  Watch early;
  const auto aborted = watchedRun(0.1, 2.0, early);
  MP_CHECK(aborted.second);
  vtkUnstructuredGrid* abortedOut = aborted.first->GetUnstructuredGridOutput();
  MP_CHECK(!abortedOut->GetPointData()->GetArray("Smooth") ||
    abortedOut->GetPointData()->GetArray("Smooth") == target->GetPointData()->GetArray("Smooth"));
  MP_CHECK(abortedOut->GetNumberOfPoints() == target->GetNumberOfPoints());
  MP_CHECK(!abortedOut->GetPointData()->GetArray("vtkValidPointMask"));
  MP_CHECK(early.Seen.size() >= 2 && std::is_sorted(early.Seen.begin(), early.Seen.end()));
  // Progress of a whole run goes up to 1 through the stages.
  Watch whole;
  MP_CHECK(!watchedRun(2.0, 2.0, whole).second);
  const std::vector<double>& all = whole.Seen;
  MP_CHECK(all.size() >= 5 && all.back() == 1.0 && std::is_sorted(all.begin(), all.end()));
  // The solve reports its progress too (from 0.9 to 0.95 of the leaf: of
  // the whole run, one leaf spanning 0.05 to 0.95, strictly between these
  // two, where nothing else reports), and stops there when asked.
  const double solveFrom = 0.05 + 0.9 * 0.9;
  const double solveTo = 0.05 + 0.9 * 0.95;
  MP_CHECK(
    std::any_of(all.begin(), all.end(), [&](double f) { return f > solveFrom && f < solveTo; }));
  Watch inSolve;
  const auto stoppedInSolve = watchedRun(solveFrom, solveTo, inSolve);
  MP_CHECK(stoppedInSolve.second);
  MP_CHECK(!stoppedInSolve.first->GetUnstructuredGridOutput()->GetPointData()->GetArray(
    "vtkValidPointMask"));
  // (Stopped at the solve's first report: nothing of the outputs' stage after it.)
  MP_CHECK(std::none_of(
    inSolve.Seen.begin(), inSolve.Seen.end(), [&](double f) { return f >= solveTo && f < 1.0; }));
  return failures == 0;
}

/// Id arrays (GlobalIds, vtkOriginalCellIds from Redistribute DataSet or
/// Extract Cells, ...) are not fields: never projected, never offered in
/// the array lists.
bool CheckIdArraysNotFields(FieldsRun& run)
{
  int failures = 0;
  vtkUnstructuredGrid* target = run.Target;
  vtkUnstructuredGrid* source = run.Source;
  vtkNew<vtkUnstructuredGrid> withIds;
  withIds->ShallowCopy(source);
  for (int association = 0; association < 2; ++association)
  {
    vtkDataSetAttributes* data = association == 0
      ? static_cast<vtkDataSetAttributes*>(withIds->GetPointData())
      : static_cast<vtkDataSetAttributes*>(withIds->GetCellData());
    const vtkIdType n =
      association == 0 ? withIds->GetNumberOfPoints() : withIds->GetNumberOfCells();
    for (const char* name : { "vtkOriginalPointIds", "vtkOriginalCellIds", "Gids" })
    {
      vtkNew<vtkIdTypeArray> ids;
      ids->SetName(name);
      ids->SetNumberOfValues(n);
      for (vtkIdType i = 0; i < n; ++i)
      {
        ids->SetValue(i, i);
      }
      if (std::string(name) == "Gids")
      {
        data->SetGlobalIds(ids);
      }
      else
      {
        data->AddArray(ids);
      }
    }
  }
  vtkNew<vtkMeshProjectionFilter> lister;
  lister->SetInputData(target);
  lister->SetSourceData(withIds);
  lister->Update();
  for (vtkDataArraySelection* list :
    { lister->GetPointDataArraySelection(), lister->GetCellDataArraySelection() })
  {
    MP_CHECK(list->GetNumberOfArrays() > 0);
    for (const char* name : { "vtkOriginalPointIds", "vtkOriginalCellIds", "Gids" })
    {
      MP_CHECK(!list->ArrayExists(name));
    }
  }
  MP_CHECK(lister->GetPointDataArraySelection()->ArrayExists("Smooth"));
  MP_CHECK(!lister->GetUnstructuredGridOutput()->GetCellData()->GetArray("vtkOriginalCellIds"));
  return failures == 0;
}

/// Every case of the filter's fields on the sample pair `targetFile`, `sourceFile` (a pair
/// with "3d" in its name is 3D: its Linear is 1 + 2x - 3y + z/2), in turn on one filter.
bool CheckFields(const char* targetFile, const char* sourceFile)
{
  int failures = 0;
  FieldsRun run(targetFile, sourceFile);
  MP_CASE(CheckCellTransfers(run));
  MP_CASE(CheckExtensive(run));
  MP_CASE(CheckMatrices(run));
  MP_CASE(CheckArraySelection(run));
  MP_CASE(CheckLumped(run));
  MP_CASE(CheckBounds(run));
  MP_CASE(CheckReuse(run));
  MP_CASE(CheckAbort(run));
  MP_CASE(CheckIdArraysNotFields(run));
  return failures == 0;
}

/**
 * With two threads the search's tasks run on VTK's thread pool, none on the
 * thread that runs the pipeline, where the GUI takes progress events: the
 * progress the first task reports in the search (every 8192 target cells)
 * must still reach the observers, from the pipeline's thread, between the
 * stages' own values around it (0.14 before the search, 0.86 after it: the
 * search's share of the bar, 0.1 to 0.9, within the leaf's, 0.05 to 0.95).
 */
bool CheckThreadedProgress()
{
  int failures = 0;
  vtkNew<vtkMeshProjectionFilter> filter;
  filter->SetNumberOfThreads(2);
  filter->SetInputData(mptest::Square(100, 100)); // 20,000 triangles: 10,000 per task
  auto source = mptest::Square(90, 90);
  for (vtkIdType p = 0; p < source->GetNumberOfPoints(); ++p)
  {
    double x[3];
    source->GetPoint(p, x);
    source->GetPoints()->SetPoint(p, x[0] + 0.003, x[1] + 0.003, x[2]); // nothing lines up
  }
  source->GetCellData()->RemoveArray("Density"); // point data only: one operator, one search
  filter->SetSourceData(source);
  struct Seen
  {
    std::thread::id Pipeline = std::this_thread::get_id();
    std::vector<double> Amounts;
    bool ElsewhereToo = false;
  } seen;
  vtkNew<vtkCallbackCommand> record;
  record->SetClientData(&seen);
  record->SetCallback([](vtkObject*, unsigned long, void* data, void* amount) {
    Seen* s = static_cast<Seen*>(data);
    s->ElsewhereToo = s->ElsewhereToo || std::this_thread::get_id() != s->Pipeline;
    s->Amounts.push_back(*static_cast<double*>(amount));
  });
  filter->AddObserver(vtkCommand::ProgressEvent, record);
  filter->Update();
  const bool inSearch = std::any_of(
    seen.Amounts.begin(), seen.Amounts.end(), [](double a) { return a > 0.15 && a < 0.85; });
  std::cout << "threaded progress:";
  for (double a : seen.Amounts)
  {
    std::cout << ' ' << a;
  }
  std::cout << "\n";
  MP_CHECK(inSearch);
  MP_CHECK(!seen.ElsewhereToo);
  MP_CHECK(std::is_sorted(seen.Amounts.begin(), seen.Amounts.end()) && !seen.Amounts.empty() &&
    seen.Amounts.back() == 1.0);
  MP_CHECK(filter->GetUnstructuredGridOutput()->GetPointData()->GetArray("Linear") != nullptr);

  // Point and cell data: two operators, two searches, one after the other
  // on the bar; it never goes back (each search starts where the one
  // before it ended).
  vtkNew<vtkMeshProjectionFilter> both;
  both->SetNumberOfThreads(1);
  both->SetInputData(mptest::Square(70, 70)); // 9,800 triangles: the search reports at 8,192
  both->SetSourceData(mptest::Square(63, 77));
  Seen twice;
  record->SetClientData(&twice);
  both->AddObserver(vtkCommand::ProgressEvent, record);
  both->Update();
  MP_CHECK(both->GetNumberOfOperatorsBuilt() == 2);
  MP_CHECK(std::is_sorted(twice.Amounts.begin(), twice.Amounts.end()) && !twice.Amounts.empty() &&
    twice.Amounts.back() == 1.0);
  return failures == 0;
}
} // namespace

int TestMeshProjectionFilterFields(int, char*[])
{
  int failures = 0;
  MP_CASE(CheckFields("lshape_target.vtu", "lshape_source.vtu"));
  MP_CASE(CheckFields("lshape3d_target.vtu", "lshape3d_source.vtu"));
  MP_CASE(CheckThreadedProgress());
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}