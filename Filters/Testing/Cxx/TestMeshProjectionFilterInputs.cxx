// SPDX-License-Identifier: BSD-3-Clause
// Bad and unusual inputs: each gets a clear error or warning and a
// well-defined output, never a crash or silent garbage.
#include "MeshProjectionTestUtilities.h"
#include "vtkDataArraySelection.h"
#include "vtkMeshProjectionFilter.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkCharArray.h"
#include "vtkCommand.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIntArray.h"
#include "vtkShortArray.h"
#include "vtkStringArray.h"
#include "vtkTestErrorObserver.h"
#include "vtkTransform.h"
#include "vtkTransformFilter.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <functional>
#include <limits>

namespace
{
struct Run
{
  vtkNew<vtkMeshProjectionFilter> Filter;
  vtkNew<vtkTest::ErrorObserver> Observer;
  Run(vtkUnstructuredGrid* target, vtkUnstructuredGrid* source,
    const std::function<void(vtkMeshProjectionFilter*)>& setUp = nullptr)
  {
    this->Filter->AddObserver(vtkCommand::ErrorEvent, this->Observer);
    this->Filter->AddObserver(vtkCommand::WarningEvent, this->Observer);
    this->Filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this->Observer);
    // The samples' label array: left out, these cases are about other arrays.
    this->Filter->GetCellDataArraySelection()->DisableArray("Region");
    this->Filter->SetInputData(target);
    this->Filter->SetSourceData(source);
    if (setUp)
    {
      setUp(this->Filter);
    }
    this->Filter->Update();
  }
  vtkUnstructuredGrid* Output() { return this->Filter->GetUnstructuredGridOutput(); }
  bool ErrorSays(const char* text)
  {
    return this->Observer->GetError() &&
      this->Observer->GetErrorMessage().find(text) != std::string::npos;
  }
  bool WarningSays(const char* text)
  {
    return this->Observer->GetWarning() &&
      this->Observer->GetWarningMessage().find(text) != std::string::npos;
  }
};

vtkSmartPointer<vtkUnstructuredGrid> Moved(vtkUnstructuredGrid* grid, double dx)
{
  vtkNew<vtkTransform> shift;
  shift->Translate(dx, 0, 0);
  vtkNew<vtkTransformFilter> move;
  move->SetTransform(shift);
  move->SetInputData(grid);
  move->Update();
  vtkSmartPointer<vtkUnstructuredGrid> result =
    vtkUnstructuredGrid::SafeDownCast(move->GetOutput());
  return result;
}

/// `grid` turned by `angle` degrees about `axis` and moved by `shift`.
vtkSmartPointer<vtkUnstructuredGrid> Turned(
  vtkUnstructuredGrid* grid, double angle, const double axis[3], const double shift[3])
{
  vtkNew<vtkTransform> turn;
  turn->Translate(shift);
  turn->RotateWXYZ(angle, axis);
  vtkNew<vtkTransformFilter> move;
  move->SetTransform(turn);
  move->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  move->SetInputData(grid);
  move->Update();
  vtkSmartPointer<vtkUnstructuredGrid> result =
    vtkUnstructuredGrid::SafeDownCast(move->GetOutput());
  return result;
}

/// Equal, or both NaN.
bool Same(double a, double b)
{
  return a == b || (std::isnan(a) && std::isnan(b));
}

/// The same arrays (names, sizes, values; NaN equal to NaN) in `a` and `b`.
bool SameArrays(vtkDataSetAttributes* a, vtkDataSetAttributes* b)
{
  if (a->GetNumberOfArrays() != b->GetNumberOfArrays())
  {
    return false;
  }
  for (int k = 0; k < a->GetNumberOfArrays(); ++k)
  {
    vtkDataArray* u = a->GetArray(k);
    vtkDataArray* v = b->GetArray(a->GetArrayName(k));
    if (!u || !v || u->GetNumberOfTuples() != v->GetNumberOfTuples() ||
      u->GetNumberOfComponents() != v->GetNumberOfComponents())
    {
      return false;
    }
    for (vtkIdType i = 0; i < u->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < u->GetNumberOfComponents(); ++c)
      {
        if (!Same(u->GetComponent(i, c), v->GetComponent(i, c)))
        {
          return false;
        }
      }
    }
  }
  return true;
}

/// `output` is `input` as it came: the same points (NaN and infinite
/// coordinates included), cells and arrays, and nothing projected (no
/// vtkValidPointMask, no CoveredFraction).
bool Unchanged(vtkUnstructuredGrid* output, vtkUnstructuredGrid* input)
{
  if (output->GetNumberOfPoints() != input->GetNumberOfPoints() ||
    output->GetNumberOfCells() != input->GetNumberOfCells() ||
    output->GetPointData()->GetArray("vtkValidPointMask") ||
    output->GetCellData()->GetArray("CoveredFraction"))
  {
    return false;
  }
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    double a[3];
    double b[3];
    output->GetPoint(i, a);
    input->GetPoint(i, b);
    if (!Same(a[0], b[0]) || !Same(a[1], b[1]) || !Same(a[2], b[2]))
    {
      return false;
    }
  }
  vtkNew<vtkIdList> a;
  vtkNew<vtkIdList> b;
  for (vtkIdType c = 0; c < input->GetNumberOfCells(); ++c)
  {
    output->GetCellPoints(c, a);
    input->GetCellPoints(c, b);
    if (output->GetCellType(c) != input->GetCellType(c) ||
      a->GetNumberOfIds() != b->GetNumberOfIds() || !std::equal(a->begin(), a->end(), b->begin()))
    {
      return false;
    }
  }
  return SameArrays(output->GetPointData(), input->GetPointData()) &&
    SameArrays(output->GetCellData(), input->GetCellData());
}

/// True when every component of every tuple of `array` satisfies `f`.
bool All(vtkDataArray* array, const std::function<bool(double)>& f)
{
  if (!array)
  {
    return false;
  }
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int k = 0; k < array->GetNumberOfComponents(); ++k)
    {
      if (!f(array->GetComponent(i, k)))
      {
        return false;
      }
    }
  }
  return true;
}

/// Nonlinear cells other than the accepted second-order ones are named,
/// with the way out (Tessellate); the output is Input unchanged.
bool CheckNonlinearCells(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> quads;
  quads->DeepCopy(source);
  vtkIdType ids[7] = { 0, 1, 2, 3, 4, 5, 6 };
  quads->InsertNextCell(VTK_BIQUADRATIC_TRIANGLE, 7, ids);
  Run run(target, quads);
  MP_CHECK(run.ErrorSays("vtkBiQuadraticTriangle"));
  MP_CHECK(run.ErrorSays("Tessellate"));
  MP_CHECK(run.Output()->GetNumberOfPoints() == target->GetNumberOfPoints());
  MP_CHECK(run.Output()->GetPointData()->GetArray("TargetId") != nullptr);
  MP_CHECK(run.Output()->GetPointData()->GetArray("Smooth") == nullptr);
  return failures == 0;
}

/// Triangles and tetrahedra in one input: a 3D mesh, its triangles left
/// out (with a warning); the 2D Input lies in it (a trace) where the
/// tetrahedron is.
bool CheckMixedDimensions(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> mixed;
  mixed->DeepCopy(source);
  mixed->GetPoints()->InsertNextPoint(0.1, 0.1, 1.0);
  vtkIdType tet[4] = { 0, 1, 2, mixed->GetNumberOfPoints() - 1 };
  mixed->InsertNextCell(VTK_TETRA, 4, tet);
  Run run(target, mixed);
  MP_CHECK(run.WarningSays("cells of lower dimension"));
  MP_CHECK(!run.ErrorSays(""));
  MP_CHECK(run.Output()->GetPointData()->GetArray("vtkValidPointMask") != nullptr);
  return failures == 0;
}

/// A 3D Input with a 2D Source: no values go to a higher dimension.
bool CheckHigherDimensionInput(vtkUnstructuredGrid* target)
{
  int failures = 0;
  auto tets = mptest::ReadSample("lshape3d_source.vtu");
  Run run(tets, target);
  MP_CHECK(run.ErrorSays("not to a mesh of a higher dimension"));
  MP_CHECK(run.Output()->GetNumberOfCells() == tets->GetNumberOfCells());
  return failures == 0;
}

/// A 2D mesh in the plane z = 5 is 2D; a Source in another plane is
/// compared in x and y, with a warning.
bool CheckSourceInOtherPlane(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  auto lifted = Moved(source, 0.0);
  for (vtkIdType i = 0; i < lifted->GetNumberOfPoints(); ++i)
  {
    double x[3];
    lifted->GetPoint(i, x);
    lifted->GetPoints()->SetPoint(i, x[0], x[1], 5.0);
  }
  Run run(target, lifted);
  MP_CHECK(run.WarningSays("plane z = 5"));
  MP_CHECK(!run.Observer->GetError());
  vtkDataArray* linear = run.Output()->GetPointData()->GetArray("Linear");
  MP_CHECK(linear != nullptr);
  for (vtkIdType i = 0; linear && i < linear->GetNumberOfTuples(); ++i)
  {
    double x[3];
    run.Output()->GetPoint(i, x);
    MP_CHECK(std::fabs(linear->GetComponent(i, 0) - (1 + 2 * x[0] - 3 * x[1])) < 1e-12);
  }
  return failures == 0;
}

/// 2D in any plane: the pair turned into the plane x = 2 (an axis plane:
/// coordinates picked, exact) and into a general plane (mapped with
/// rounding) gives the same pairs and the same values as in z = 0; a
/// Source in a plane that is not parallel is an error.
bool CheckAnyPlane(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkMeshProjectionFilter> flat;
  flat->SetInputData(target);
  flat->SetSourceData(source);
  flat->Update();
  vtkDataArray* expected = flat->GetUnstructuredGridOutput()->GetPointData()->GetArray("Smooth");
  const double yAxis[3] = { 0, 1, 0 };
  const double general[3] = { 0.3, -0.5, 0.8 };
  const double shiftX[3] = { 2, 0, 0 };
  const double shift[3] = { 0.7, -1.3, 2.1 };
  for (int k = 0; k < 2; ++k)
  {
    const double* axis = k == 0 ? yAxis : general;
    const double angle = k == 0 ? 90.0 : 37.0;
    const double* by = k == 0 ? shiftX : shift;
    Run run(Turned(target, angle, axis, by), Turned(source, angle, axis, by));
    MP_CHECK(!run.Observer->GetError() && !run.Observer->GetWarning());
    // The general plane's rounding may split a boundary contact differently.
    MP_CHECK(k == 1 || run.Filter->GetNumberOfIntersections() == flat->GetNumberOfIntersections());
    MP_CHECK(std::fabs(run.Filter->GetCoveredMeasure() - flat->GetCoveredMeasure()) < 1e-12);
    vtkDataArray* smooth = run.Output()->GetPointData()->GetArray("Smooth");
    MP_CHECK(smooth && expected && smooth->GetNumberOfTuples() == expected->GetNumberOfTuples());
    double worst = 0.0;
    for (vtkIdType i = 0; smooth && expected && i < smooth->GetNumberOfTuples(); ++i)
    {
      worst = std::max(worst, std::fabs(smooth->GetComponent(i, 0) - expected->GetComponent(i, 0)));
    }
    MP_CHECK(worst < (k == 0 ? 1e-12 : 1e-10));
  }
  // The Source's triangles wound the other way: the same plane, the same result.
  auto turned = Turned(source, 37.0, general, shift);
  vtkNew<vtkUnstructuredGrid> rewound;
  rewound->DeepCopy(turned);
  vtkNew<vtkCellArray> reversed;
  for (vtkIdType c = 0; c < turned->GetNumberOfCells(); ++c)
  {
    vtkIdType npts;
    const vtkIdType* pts;
    turned->GetCells()->GetCellAtId(c, npts, pts);
    const vtkIdType flipped[3] = { pts[0], pts[2], pts[1] };
    reversed->InsertNextCell(3, flipped);
  }
  rewound->SetCells(VTK_TRIANGLE, reversed);
  Run rewoundRun(Turned(target, 37.0, general, shift), rewound);
  MP_CHECK(!rewoundRun.Observer->GetError() && !rewoundRun.Observer->GetWarning());
  MP_CHECK(std::fabs(rewoundRun.Filter->GetCoveredMeasure() - flat->GetCoveredMeasure()) < 1e-12);
  Run tilted(target, Turned(source, 10.0, yAxis, shiftX));
  MP_CHECK(tilted.ErrorSays("not parallel"));
  MP_CHECK(Unchanged(tilted.Output(), target));
  return failures == 0;
}

/// NaN coordinates.
bool CheckNaNCoordinates(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> broken;
  broken->DeepCopy(source);
  broken->GetPoints()->SetPoint(5, std::numeric_limits<double>::quiet_NaN(), 0, 0);
  Run run(target, broken);
  MP_CHECK(run.ErrorSays("Source has a point with a NaN or infinite coordinate (point 5)"));
  MP_CHECK(Unchanged(run.Output(), target));
  // A NaN point that no cell uses is no error: the projection is the
  // one without it.
  vtkNew<vtkUnstructuredGrid> extra;
  extra->DeepCopy(source);
  extra->GetPoints()->InsertNextPoint(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  for (int a = 0; a < extra->GetPointData()->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* values = extra->GetPointData()->GetArray(a);
    if (values)
    {
      values->InsertNextTuple(values->GetTuple(0));
    }
  }
  Run unused(target, extra);
  Run plain(target, source);
  MP_CHECK(!unused.Observer->GetError());
  MP_CHECK(!plain.Observer->GetError());
  vtkDataArray* got = unused.Output()->GetPointData()->GetArray("Linear");
  vtkDataArray* want = plain.Output()->GetPointData()->GetArray("Linear");
  MP_CHECK(got && want && got->GetNumberOfTuples() == want->GetNumberOfTuples());
  for (vtkIdType i = 0; got && want && i < want->GetNumberOfTuples(); ++i)
  {
    MP_CHECK(got->GetTuple1(i) == want->GetTuple1(i) ||
      (std::isnan(got->GetTuple1(i)) && std::isnan(want->GetTuple1(i))));
  }
  return failures == 0;
}

/// Infinite coordinates, in Source and in Input, 2D and 3D: an error and
/// Input unchanged, nothing projected.
bool CheckInfiniteCoordinates(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  const double inf = std::numeric_limits<double>::infinity();
  vtkNew<vtkUnstructuredGrid> farSource;
  farSource->DeepCopy(source);
  farSource->GetPoints()->SetPoint(5, inf, 0, 0);
  Run bad(target, farSource);
  MP_CHECK(bad.ErrorSays("Source has a point with a NaN or infinite coordinate (point 5)"));
  MP_CHECK(Unchanged(bad.Output(), target));

  vtkNew<vtkUnstructuredGrid> farTarget;
  farTarget->DeepCopy(target);
  farTarget->GetPoints()->SetPoint(7, 0.1, -inf, 0);
  Run badInput(farTarget, source);
  MP_CHECK(badInput.ErrorSays("Input has a point with a NaN or infinite coordinate (point 7)"));
  MP_CHECK(Unchanged(badInput.Output(), farTarget));
  MP_CHECK(std::isinf(badInput.Output()->GetPoint(7)[1]));

  auto tets = mptest::ReadSample("lshape3d_source.vtu");
  auto tetTarget = mptest::ReadSample("lshape3d_target.vtu");
  vtkNew<vtkUnstructuredGrid> far3D;
  far3D->DeepCopy(tetTarget);
  far3D->GetPoints()->SetPoint(3, 0.1, 0.1, inf);
  Run bad3D(far3D, tets);
  MP_CHECK(bad3D.ErrorSays("Input has a point with a NaN or infinite coordinate (point 3)"));
  MP_CHECK(Unchanged(bad3D.Output(), far3D));
  vtkNew<vtkUnstructuredGrid> farTets;
  farTets->DeepCopy(tets);
  farTets->GetPoints()->SetPoint(3, -inf, 0.1, 0.1);
  Run badSource3D(tetTarget, farTets);
  MP_CHECK(badSource3D.ErrorSays("Source has a point with a NaN or infinite coordinate (point 3)"));
  MP_CHECK(Unchanged(badSource3D.Output(), tetTarget));
  return failures == 0;
}

/// Coordinates beyond the range of the exact predicates.
bool CheckHugeCoordinates(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> huge;
  huge->DeepCopy(source);
  huge->GetPoints()->SetPoint(5, 1e120, 0, 0);
  Run run(target, huge);
  MP_CHECK(run.ErrorSays("between 1e-100 and 1e100"));
  MP_CHECK(run.Output()->GetPointData()->GetArray("Smooth") == nullptr);
  return failures == 0;
}

/// Not planar: a surface in 3D. The facets around the lifted point are
/// tilted far beyond MaximumNormalAngle and meet nothing: that point is
/// invalid, every other one has flat facets and is exact.
bool CheckBentSurface(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> bent;
  bent->DeepCopy(target);
  bent->GetPoints()->SetPoint(7, 0.1, 0.1, 0.5);
  Run run(bent, source);
  MP_CHECK(!run.Observer->GetError());
  vtkDataArray* linear = run.Output()->GetPointData()->GetArray("Linear");
  vtkDataArray* mask = run.Output()->GetPointData()->GetArray("vtkValidPointMask");
  MP_CHECK(linear && mask);
  for (vtkIdType i = 0; linear && mask && i < linear->GetNumberOfTuples(); ++i)
  {
    double x[3];
    run.Output()->GetPoint(i, x);
    MP_CHECK(mask->GetComponent(i, 0) == (i == 7 ? 0 : 1));
    MP_CHECK(i == 7 || std::fabs(linear->GetComponent(i, 0) - (1 + 2 * x[0] - 3 * x[1])) < 1e-12);
  }
  return failures == 0;
}

/// No overlap: a warning, every point invalid and filled with NaN.
bool CheckNoOverlap(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  auto away = Moved(source, 10.0);
  Run run(target, away);
  MP_CHECK(run.WarningSays("do not overlap"));
  MP_CHECK(!run.Observer->GetError());
  vtkDataArray* smooth = run.Output()->GetPointData()->GetArray("Smooth");
  vtkDataArray* mask = run.Output()->GetPointData()->GetArray("vtkValidPointMask");
  MP_CHECK(smooth && mask);
  for (vtkIdType i = 0; smooth && mask && i < smooth->GetNumberOfTuples(); ++i)
  {
    MP_CHECK(std::isnan(smooth->GetComponent(i, 0)) && mask->GetComponent(i, 0) == 0);
  }
  return failures == 0;
}

/// Partial overlap: covered points exact on a linear field, the others
/// flagged and set to the fill value.
bool CheckPartialOverlap(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  auto half = Moved(source, 1.0);
  Run run(target, half);
  run.Filter->FillWithNaNOff();
  run.Filter->SetFillValue(-999);
  run.Filter->Update();
  vtkDataArray* linear = run.Output()->GetPointData()->GetArray("Linear");
  vtkDataArray* mask = run.Output()->GetPointData()->GetArray("vtkValidPointMask");
  vtkIdType valid = 0;
  for (vtkIdType i = 0; linear && mask && i < linear->GetNumberOfTuples(); ++i)
  {
    double x[3];
    run.Output()->GetPoint(i, x);
    if (mask->GetComponent(i, 0))
    {
      ++valid;
      MP_CHECK(std::fabs(linear->GetComponent(i, 0) - (1 + 2 * (x[0] - 1) - 3 * x[1])) < 1e-11);
    }
    else
    {
      MP_CHECK(linear->GetComponent(i, 0) == -999);
    }
  }
  MP_CHECK(valid > 0 && valid < target->GetNumberOfPoints());
  return failures == 0;
}

/// Empty source: a warning, all invalid, nothing covered.
bool CheckEmptySource(vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> empty;
  Run run(target, empty);
  MP_CHECK(!run.Observer->GetError());
  MP_CHECK(run.WarningSays("Source has no cells: every projected point is invalid."));
  MP_CHECK(run.WarningSays("Source has no arrays to project"));
  MP_CHECK(run.Output()->GetNumberOfPoints() == target->GetNumberOfPoints());
  vtkDataArray* mask = run.Output()->GetPointData()->GetArray("vtkValidPointMask");
  MP_CHECK(mask && mask->GetNumberOfTuples() == target->GetNumberOfPoints());
  MP_CHECK(All(mask, [](double m) { return m == 0; }));
  MP_CHECK(
    All(run.Output()->GetCellData()->GetArray("CoveredFraction"), [](double f) { return f == 0; }));
  // Input's own TargetId and the mask: nothing to project.
  MP_CHECK(run.Output()->GetPointData()->GetNumberOfArrays() == 2);
  MP_CHECK(run.Output()->GetPointData()->GetArray("TargetId") != nullptr);
  return failures == 0;
}

/// An empty Source that still declares its arrays (no points, no cells):
/// every projected array is there, NaN everywhere (FillWithNaN), or the
/// FillValue.
bool CheckEmptySourceWithArrays(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> empty;
  empty->GetPointData()->CopyAllocate(source->GetPointData(), 0);
  MP_CHECK(empty->GetPointData()->GetArray("Velocity") != nullptr);
  Run run(target, empty);
  MP_CHECK(!run.Observer->GetError());
  MP_CHECK(run.WarningSays("Source has no cells: every projected point is invalid."));
  vtkPointData* pd = run.Output()->GetPointData();
  MP_CHECK(All(pd->GetArray("vtkValidPointMask"), [](double m) { return m == 0; }));
  for (const char* name : { "Smooth", "Linear", "Velocity" })
  {
    vtkDataArray* u = pd->GetArray(name);
    MP_CHECK(u && u->GetNumberOfTuples() == target->GetNumberOfPoints());
    MP_CHECK(All(u, [](double v) { return std::isnan(v); }));
  }
  MP_CHECK(pd->GetArray("Velocity") && pd->GetArray("Velocity")->GetNumberOfComponents() == 3);
  run.Filter->FillWithNaNOff();
  run.Filter->SetFillValue(-999);
  run.Filter->Update();
  pd = run.Output()->GetPointData();
  MP_CHECK(All(pd->GetArray("Velocity"), [](double v) { return v == -999; }));
  MP_CHECK(All(pd->GetArray("vtkValidPointMask"), [](double m) { return m == 0; }));
  return failures == 0;
}

/// Non-numeric arrays are skipped with a warning; other types converted.
bool CheckNonNumericArrays(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> typed;
  typed->DeepCopy(source);
  vtkNew<vtkStringArray> names;
  names->SetName("Names");
  names->SetNumberOfValues(typed->GetNumberOfPoints());
  typed->GetPointData()->AddArray(names);
  vtkNew<vtkIntArray> ones;
  ones->SetName("Ones");
  ones->SetNumberOfValues(typed->GetNumberOfPoints());
  ones->Fill(1);
  typed->GetPointData()->AddArray(ones);
  // An integer array is a label array by default (its type kept, no
  // warning); treated as numbers (CATEGORICAL_SELECTED, not named), a real
  // array, with the warning.
  for (const bool numbers : { false, true })
  {
    Run run(target, typed, [numbers](vtkMeshProjectionFilter* f) {
      f->SetCategoricalMode(numbers ? vtkMeshProjectionFilter::CATEGORICAL_SELECTED
                                    : vtkMeshProjectionFilter::CATEGORICAL_AUTOMATIC);
    });
    MP_CHECK(
      run.WarningSays("Source point array 'Names' is not numeric (vtkStringArray): skipped."));
    MP_CHECK(run.WarningSays("Source point array 'Ones' holds integers (vtkIntArray)") == numbers);
    MP_CHECK(run.Output()->GetPointData()->GetAbstractArray("Names") == nullptr);
    vtkDataArray* projected = run.Output()->GetPointData()->GetArray("Ones");
    MP_CHECK(projected != nullptr);
    MP_CHECK(projected &&
      (numbers ? vtkDoubleArray::SafeDownCast(projected) != nullptr
               : vtkIntArray::SafeDownCast(projected) != nullptr));
    for (vtkIdType i = 0; projected && i < projected->GetNumberOfTuples(); ++i)
    {
      MP_CHECK(std::fabs(projected->GetComponent(i, 0) - 1.0) < 1e-13);
    }
  }
  return failures == 0;
}

/// Integer arrays (labels, ids) that the user treats as numbers
/// (CATEGORICAL_SELECTED without naming them) are projected as real values,
/// with a warning naming each; vtkValidPointMask and vtkGhostType are not
/// projected (nor warned about). By default (CATEGORICAL_AUTOMATIC) the
/// single-component ones are labels: no warning, their type kept, only
/// Source labels; a two-component integer array stays numbers, warned.
bool CheckIntegerArrays(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkUnstructuredGrid> labelled;
  labelled->DeepCopy(source);
  const vtkIdType n = labelled->GetNumberOfPoints();
  vtkNew<vtkIntArray> labels;
  labels->SetName("Labels");
  vtkNew<vtkDoubleArray> real;
  real->SetName("LabelsAsReal");
  vtkNew<vtkShortArray> pair;
  pair->SetName("Pair");
  pair->SetNumberOfComponents(2);
  vtkNew<vtkCharArray> sourceMask;
  sourceMask->SetName("vtkValidPointMask");
  vtkNew<vtkUnsignedCharArray> ghosts;
  ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
  for (vtkIdType i = 0; i < n; ++i)
  {
    const int label = labelled->GetPoint(i)[0] > 1.0 ? 7 : 3;
    labels->InsertNextValue(label);
    real->InsertNextValue(label);
    pair->InsertNextTuple2(3, -7);
    sourceMask->InsertNextValue(0);
    ghosts->InsertNextValue(0);
  }
  labelled->GetPointData()->AddArray(labels);
  labelled->GetPointData()->AddArray(real);
  labelled->GetPointData()->AddArray(pair);
  labelled->GetPointData()->AddArray(sourceMask);
  labelled->GetPointData()->AddArray(ghosts);
  Run asLabels(target, labelled);
  MP_CHECK(!asLabels.Observer->GetError());
  MP_CHECK(!asLabels.WarningSays("'Labels' holds integers"));
  MP_CHECK(asLabels.WarningSays("Source point array 'Pair' holds integers (vtkShortArray)"));
  vtkIntArray* label =
    vtkIntArray::SafeDownCast(asLabels.Output()->GetPointData()->GetArray("Labels"));
  MP_CHECK(label != nullptr);
  vtkIdType threes = 0;
  vtkIdType sevens = 0;
  for (vtkIdType i = 0; label && i < label->GetNumberOfValues(); ++i)
  {
    threes += label->GetValue(i) == 3;
    sevens += label->GetValue(i) == 7;
  }
  MP_CHECK(label && threes > 0 && sevens > 0 && threes + sevens == label->GetNumberOfValues());
  Run run(target, labelled, [](vtkMeshProjectionFilter* f) {
    f->SetCategoricalMode(vtkMeshProjectionFilter::CATEGORICAL_SELECTED);
  });
  MP_CHECK(!run.Observer->GetError());
  MP_CHECK(run.WarningSays("Source point array 'Labels' holds integers (vtkIntArray): it is "
                           "projected as real values (a 0/1 indicator becomes a covered "
                           "fraction, but labels and ids do not carry over: set CategoricalMode "
                           "to CATEGORICAL_AUTOMATIC, or name it in CategoricalArrays, to "
                           "project it as labels, or deselect it)."));
  MP_CHECK(run.WarningSays("Source point array 'Pair' holds integers (vtkShortArray)"));
  const std::string warnings = run.Observer->GetWarningMessage();
  for (const char* quiet :
    { "'LabelsAsReal'", "'Smooth'", "'vtkValidPointMask'", "'vtkGhostType'" })
  {
    MP_CHECK(warnings.find(quiet) == std::string::npos);
  }
  vtkPointData* pd = run.Output()->GetPointData();
  vtkDataArray* projected = pd->GetArray("Labels");
  vtkDataArray* reference = pd->GetArray("LabelsAsReal");
  MP_CHECK(vtkDoubleArray::SafeDownCast(projected) && reference);
  vtkIdType between = 0;
  for (vtkIdType i = 0; projected && reference && i < projected->GetNumberOfTuples(); ++i)
  {
    const double v = projected->GetComponent(i, 0);
    MP_CHECK(std::fabs(v - reference->GetComponent(i, 0)) < 1e-13);
    between += std::fabs(v - 3) > 1e-3 && std::fabs(v - 7) > 1e-3;
  }
  MP_CHECK(between > 0); // the projection mixes labels where they change
  vtkDataArray* projectedPair = pd->GetArray("Pair");
  MP_CHECK(
    vtkDoubleArray::SafeDownCast(projectedPair) && projectedPair->GetNumberOfComponents() == 2);
  for (vtkIdType i = 0; projectedPair && i < projectedPair->GetNumberOfTuples(); ++i)
  {
    MP_CHECK(std::fabs(projectedPair->GetComponent(i, 0) - 3) < 1e-13);
    MP_CHECK(std::fabs(projectedPair->GetComponent(i, 1) + 7) < 1e-13);
  }
  // The output's mask is the filter's own (all covered), not Source's zeros.
  vtkDataArray* mask = pd->GetArray("vtkValidPointMask");
  MP_CHECK(vtkCharArray::SafeDownCast(mask));
  MP_CHECK(All(mask, [](double m) { return m == 1; }));
  MP_CHECK(pd->GetArray(vtkDataSetAttributes::GhostArrayName()) == nullptr);
  return failures == 0;
}

/// No source at all.
bool CheckNoSource(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkNew<vtkMeshProjectionFilter> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->SetInputData(target);
  filter->Update();
  // The filter's own error, and Input passed through unchanged.
  MP_CHECK(observer->GetError());
  const std::string error = observer->GetErrorMessage();
  MP_CHECK(
    error.find("No Source is connected (input port 1): nothing to project.") != std::string::npos);
  MP_CHECK(Unchanged(filter->GetUnstructuredGridOutput(), target));
  // A Source removed after a good run: no stale projected arrays remain.
  vtkNew<vtkMeshProjectionFilter> again;
  again->SetInputData(target);
  again->SetSourceData(source);
  again->Update();
  MP_CHECK(
    again->GetUnstructuredGridOutput()->GetPointData()->GetArray("vtkValidPointMask") != nullptr);
  vtkNew<vtkTest::ErrorObserver> secondObserver;
  again->AddObserver(vtkCommand::ErrorEvent, secondObserver);
  again->RemoveAllInputConnections(1);
  again->Update();
  MP_CHECK(secondObserver->GetError());
  MP_CHECK(Unchanged(again->GetUnstructuredGridOutput(), target));
  return failures == 0;
}

} // namespace

int TestMeshProjectionFilterInputs(int, char*[])
{
  int failures = 0;
  auto source = mptest::ReadSample("lshape_source.vtu");
  auto target = mptest::ReadSample("lshape_target.vtu");
  MP_CASE(CheckNonlinearCells(source, target));
  MP_CASE(CheckMixedDimensions(source, target));
  MP_CASE(CheckHigherDimensionInput(target));
  MP_CASE(CheckSourceInOtherPlane(source, target));
  MP_CASE(CheckAnyPlane(source, target));
  MP_CASE(CheckNaNCoordinates(source, target));
  MP_CASE(CheckInfiniteCoordinates(source, target));
  MP_CASE(CheckHugeCoordinates(source, target));
  MP_CASE(CheckBentSurface(source, target));
  MP_CASE(CheckNoOverlap(source, target));
  MP_CASE(CheckPartialOverlap(source, target));
  MP_CASE(CheckEmptySource(target));
  MP_CASE(CheckEmptySourceWithArrays(source, target));
  MP_CASE(CheckNonNumericArrays(source, target));
  MP_CASE(CheckIntegerArrays(source, target));
  MP_CASE(CheckNoSource(source, target));
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
