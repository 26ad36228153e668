// SPDX-License-Identifier: BSD-3-Clause
// Corrupt and hostile data at the VTK boundary (run under AddressSanitizer
// too, see Testing/Fuzzing/Filter):
// * ids, offsets, cell sizes, cell types, polyhedron face streams, array
//   lengths that point outside their arrays, on either port, in every
//   container the filter reads: a clear error naming the cell and the value,
//   Input passed through, no read outside the arrays;
// * NaN and infinite Source values: the Source cells using them are a hole
//   for that array only (linear fields stay exact elsewhere, the integral
//   over the rest is conserved, masks say where values are missing), and
//   operators kept across executions follow a moving hole.
#include "MeshProjectionTestUtilities.h"
#include "vtkMeshProjectionFilter.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkCharArray.h"
#include "vtkCommand.h"
#include "vtkDataArraySelection.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkIdTypeArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace
{
vtkSmartPointer<vtkUnstructuredGrid> HexAndPolyhedron()
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  for (int i = 0; i <= 2; ++i)
  {
    for (int j = 0; j <= 1; ++j)
    {
      for (int k = 0; k <= 1; ++k)
      {
        points->InsertNextPoint(i, j, k);
      }
    }
  }
  grid->SetPoints(points);
  // Point (i, j, k) is 4i + 2j + k.
  auto id = [](int i, int j, int k) { return vtkIdType(4 * i + 2 * j + k); };
  const vtkIdType hex[8] = { id(0, 0, 0), id(1, 0, 0), id(1, 1, 0), id(0, 1, 0), id(0, 0, 1),
    id(1, 0, 1), id(1, 1, 1), id(0, 1, 1) };
  grid->InsertNextCell(VTK_HEXAHEDRON, 8, hex);
  vtkIdType p[8];
  for (int n = 0; n < 8; ++n)
  {
    p[n] = hex[n] + 4;
  }
  const vtkIdType faces[] = { 6, 4, p[0], p[3], p[2], p[1], 4, p[4], p[5], p[6], p[7], 4, p[0],
    p[1], p[5], p[4], 4, p[2], p[3], p[7], p[6], 4, p[1], p[2], p[6], p[5], 4, p[0], p[4], p[7],
    p[3] };
  grid->InsertNextCell(VTK_POLYHEDRON, 8, p, 6, faces + 1);
  return grid;
}

struct Result
{
  vtkSmartPointer<vtkDataSet> Output;
  std::string Errors;
  std::string Warnings;
  int Built = 0;
};

Result Project(vtkDataObject* target, vtkDataObject* source,
  const std::function<void(vtkMeshProjectionFilter*)>& set = nullptr)
{
  vtkNew<vtkMeshProjectionFilter> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->SetInputData(target);
  filter->SetSourceData(source);
  if (set)
  {
    set(filter);
  }
  filter->Update();
  Result r;
  r.Output = vtkDataSet::SafeDownCast(filter->GetOutput());
  r.Errors = observer->GetError() ? observer->GetErrorMessage() : "";
  r.Warnings = observer->GetWarning() ? observer->GetWarningMessage() : "";
  r.Built = filter->GetNumberOfOperatorsBuilt();
  return r;
}

template <class T>
vtkSmartPointer<T> Copy(T* data)
{
  auto copy = vtkSmartPointer<T>::New();
  copy->DeepCopy(data);
  return copy;
}

bool Contains(const std::string& text, const std::string& part)
{
  const bool found = text.find(part) != std::string::npos;
  if (!found)
  {
    std::cerr << "expected \"" << part << "\" in: " << text << std::endl;
  }
  return found;
}

/// A corrupt cell, in `source` or `hexes` (HexAndPolyhedron), and the error expected for it.
struct Corruption
{
  const char* What;
  std::function<vtkSmartPointer<vtkDataObject>()> Make;
  const char* Expected;
};

/**
 * Corrupt cells, in every container the filter reads: copies of `source` (a triangle mesh) or
 * of `hexes` (HexAndPolyhedron; the corruption's name says polyhedron or hexahedron) or
 * polydata on `source`'s points, each with one id, offset, size, type, face stream or array
 * out of its range. The copies are made when Make is called; `source` and `hexes` must
 * live until then.
 */
std::vector<Corruption> Corruptions(vtkUnstructuredGrid* source, vtkUnstructuredGrid* hexes)
{
  auto corruptId = [source](vtkIdType id) {
    return [source, id]() {
      auto g = Copy(source);
      g->GetCells()->GetConnectivityArray()->SetComponent(16, 0, static_cast<double>(id));
      return vtkSmartPointer<vtkDataObject>(g);
    };
  };
  const vtkIdType big = 1000000000000;
  return {
    { "a point id of 10^12", corruptId(big), "cell 5 refers to point 1000000000000" },
    { "a point id past the end", corruptId(source->GetNumberOfPoints() + 100),
      "cell 5 refers to point 675, which does not exist (575 points)" },
    { "a negative point id", corruptId(-5), "cell 5 refers to point -5" },
    { "decreasing offsets",
      [=]() {
        auto g = Copy(source);
        g->GetCells()->GetOffsetsArray()->SetComponent(8, 0, 3);
        return vtkSmartPointer<vtkDataObject>(g);
      },
      "cell 7 has offsets 21 then 3" },
    { "offsets past the connectivity",
      [=]() {
        auto g = Copy(source);
        vtkDataArray* o = g->GetCells()->GetOffsetsArray();
        o->SetComponent(o->GetNumberOfTuples() - 1, 0, 1e9);
        return vtkSmartPointer<vtkDataObject>(g);
      },
      "into a connectivity array of 3168 ids" },
    { "a triangle of 2 points",
      [=]() {
        auto g = Copy(source);
        g->GetCellTypesArray()->SetValue(7, VTK_TRIANGLE);
        g->GetCells()->GetOffsetsArray()->SetComponent(7, 0, 20);
        return vtkSmartPointer<vtkDataObject>(g);
      },
      "cell 6 has 2 points where its type needs 3" },
    { "an unknown cell type",
      [=]() {
        auto g = Copy(source);
        g->GetCellTypesArray()->SetValue(9, 17);
        return vtkSmartPointer<vtkDataObject>(g);
      },
      "cell 9 has the unknown cell type 17" },
    { "fewer cell types than cells",
      [=]() {
        auto g = Copy(source);
        g->GetCellTypesArray()->SetNumberOfValues(100);
        return vtkSmartPointer<vtkDataObject>(g);
      },
      "has 1056 cells but 100 cell types" },
    { "a hexahedron's point id of 10^12",
      [=]() {
        auto g = Copy(hexes);
        g->GetCells()->GetConnectivityArray()->SetComponent(3, 0, 1e12);
        return vtkSmartPointer<vtkDataObject>(g);
      },
      "cell 0 refers to point 1000000000000" },
    { "a polyhedron face's point id past the end",
      [=]() {
        auto g = Copy(hexes);
        g->GetFaces()->SetValue(g->GetFaceLocations()->GetValue(1) + 4, 40);
        return vtkSmartPointer<vtkDataObject>(g);
      },
      "cell 1 is a polyhedron whose face 0 refers to point 40" },
    { "a polyhedron face stream past the end",
      [=]() {
        auto g = Copy(hexes);
        g->GetFaces()->SetValue(g->GetFaceLocations()->GetValue(1) + 1, 1000);
        return vtkSmartPointer<vtkDataObject>(g);
      },
      "face 0 has 1000 points, past the end of the faces array" },
    { "a polyhedron's face location past the end",
      [=]() {
        auto g = Copy(hexes);
        g->GetFaceLocations()->SetValue(1, 999);
        return vtkSmartPointer<vtkDataObject>(g);
      },
      "face stream starts at 999" },
    { "a polygon's point id of 10^12 in polydata",
      [=]() {
        vtkNew<vtkPolyData> p;
        p->SetPoints(source->GetPoints());
        auto cells = Copy(source->GetCells());
        cells->GetConnectivityArray()->SetComponent(30, 0, 1e12);
        p->SetPolys(cells);
        return vtkSmartPointer<vtkDataObject>(p);
      },
      "polygons: cell 10 refers to point 1000000000000" },
    { "a polygon of 2 points in polydata",
      [=]() {
        vtkNew<vtkPolyData> p;
        p->SetPoints(source->GetPoints());
        vtkNew<vtkCellArray> polys;
        const vtkIdType two[2] = { 0, 1 };
        polys->InsertNextCell(2, two);
        p->SetPolys(polys);
        return vtkSmartPointer<vtkDataObject>(p);
      },
      "cell 0 has 2 points where its type needs at least 3" },
    { "a ghost array shorter than the cells",
      [=]() {
        auto g = Copy(source);
        g->GetCellData()->AddArray(mptest::GhostArray(3));
        return vtkSmartPointer<vtkDataObject>(g);
      },
      "cell ghost array has 3 tuples of 1 components for 1056 cells" },
  };
}

/// Corruption `c` on either port: an error naming the cell and the value;
/// the output is Input as it came.
bool CheckCorruption(const Corruption& c, vtkUnstructuredGrid* target, vtkUnstructuredGrid* hexes)
{
  int failures = 0;
  vtkSmartPointer<vtkDataObject> bad = c.Make();
  const bool volume = std::string(c.What).find("hedr") != std::string::npos;
  vtkSmartPointer<vtkDataObject> good =
    volume ? vtkSmartPointer<vtkDataObject>(hexes) : vtkSmartPointer<vtkDataObject>(target);
  for (int port = 0; port < 2; ++port)
  {
    std::cout << c.What << " in " << (port == 0 ? "Input" : "Source") << std::endl;
    const Result r = port == 0 ? Project(bad, good) : Project(good, bad);
    MP_CHECK(Contains(r.Errors, port == 0 ? "Input" : "Source"));
    MP_CHECK(Contains(r.Errors, c.Expected));
    MP_CHECK(Contains(r.Errors, "corrupt"));
    vtkDataSet* in = vtkDataSet::SafeDownCast(port == 0 ? bad : good);
    MP_CHECK(r.Output && r.Output->GetNumberOfPoints() == in->GetNumberOfPoints());
    MP_CHECK(r.Output && !r.Output->GetPointData()->GetArray("vtkValidPointMask"));
  }
  return failures == 0;
}

/// A corrupt block of a composite Source is named before anything reads it.
bool CheckCorruptBlock(
  vtkUnstructuredGrid* source, vtkUnstructuredGrid* target, const Corruption& corrupt)
{
  int failures = 0;
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, source);
  blocks->SetBlock(1, corrupt.Make());
  const Result r = Project(target, blocks);
  MP_CHECK(
    Contains(r.Errors, "Source block of flat index 2: cell 5 refers to point 1000000000000"));
  return failures == 0;
}

/// Source arrays shorter than the points: not projected, with a warning;
/// the others are (in a composite Source too). Input's are its own.
bool CheckShortArrays(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  auto s = Copy(source);
  s->GetPointData()->GetArray("Other")->SetNumberOfTuples(10);
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, s);
  for (vtkDataObject* from :
    { static_cast<vtkDataObject*>(s), static_cast<vtkDataObject*>(blocks) })
  {
    const Result r = Project(target, from);
    MP_CHECK(r.Errors.empty());
    MP_CHECK(Contains(r.Warnings, "'Other' has 10 tuples for 575"));
    MP_CHECK(r.Output->GetPointData()->GetArray("Linear"));
    // (Input's own array, passed through)
    MP_CHECK(
      r.Output->GetPointData()->GetArray("Other") == target->GetPointData()->GetArray("Other"));
  }
  auto t = Copy(target);
  t->GetPointData()->GetArray("Other")->SetNumberOfTuples(10);
  const Result r = Project(t, source);
  MP_CHECK(r.Errors.empty() && r.Output->GetPointData()->GetArray("Linear"));
  return failures == 0;
}

/// Point array `name` of `r` as a mask (null when it is not one).
vtkCharArray* ValidMask(const Result& r, const char* name)
{
  return vtkCharArray::SafeDownCast(r.Output->GetPointData()->GetArray(name));
}

/// The largest error of `r`'s point array `array` against 1 + 2x - 3y,
/// over the points `mask` says are valid (all of them without a mask).
double LinearError(const Result& r, const char* array, vtkCharArray* mask)
{
  double e = 0;
  vtkDataArray* u = r.Output->GetPointData()->GetArray(array);
  for (vtkIdType i = 0; i < r.Output->GetNumberOfPoints(); ++i)
  {
    double x[3];
    r.Output->GetPoint(i, x);
    if (!mask || mask->GetValue(i))
    {
      e = std::max(e, std::fabs(u->GetComponent(i, 0) - (1 + 2 * x[0] - 3 * x[1])));
    }
  }
  return e;
}

/// One NaN, then one Inf, among 625 values: the field is not wiped out.
bool CheckIsolatedNaNValues(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  for (double spoil : { std::numeric_limits<double>::quiet_NaN(), HUGE_VAL })
  {
    auto s = Copy(source);
    s->GetPointData()->GetArray("Linear")->SetComponent(312, 0, spoil);
    const Result r = Project(target, s);
    MP_CHECK(Contains(r.Warnings, "'Linear' has 1 NaN or infinite values: the 6 Source cells"));
    vtkDataArray* u = r.Output->GetPointData()->GetArray("Linear");
    vtkIdType finite = 0;
    for (vtkIdType i = 0; i < u->GetNumberOfTuples(); ++i)
    {
      finite += std::isfinite(u->GetComponent(i, 0));
    }
    MP_CHECK(finite == target->GetNumberOfPoints());
    MP_CHECK(LinearError(r, "Linear", nullptr) < 1e-6);
  }
  return failures == 0;
}

/// A copy of `source` whose Linear is NaN in the disc of radius 0.25
/// around (0.6, 0.4); how many points that spoils in `spoiled`.
vtkSmartPointer<vtkUnstructuredGrid> WithNaNDisc(vtkUnstructuredGrid* source, vtkIdType* spoiled)
{
  auto s = Copy(source);
  vtkDataArray* u = s->GetPointData()->GetArray("Linear");
  *spoiled = 0;
  for (vtkIdType i = 0; i < s->GetNumberOfPoints(); ++i)
  {
    double x[3];
    s->GetPoint(i, x);
    if (std::hypot(x[0] - 0.6, x[1] - 0.4) < 0.25)
    {
      u->SetComponent(i, 0, std::nan(""));
      ++*spoiled;
    }
  }
  return s;
}

/// A region of NaN: target points whose support lies in the hole are
/// invalid for that array alone (a mask of its own), the others exact.
bool CheckNaNRegion(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkIdType spoiled = 0;
  auto s = WithNaNDisc(source, &spoiled);
  const Result r = Project(target, s);
  vtkCharArray* own = ValidMask(r, "vtkValidPointMask_Linear");
  vtkCharArray* all = ValidMask(r, "vtkValidPointMask");
  MP_CHECK(own && all && !ValidMask(r, "vtkValidPointMask_Other"));
  vtkIdType invalid = 0;
  for (vtkIdType i = 0; own && all && i < r.Output->GetNumberOfPoints(); ++i)
  {
    double x[3];
    r.Output->GetPoint(i, x);
    invalid += own->GetValue(i) == 0;
    MP_CHECK(all->GetValue(i) == 1);
    // Inside the hole, less a source and a target cell: invalid, NaN.
    if (std::hypot(x[0] - 0.6, x[1] - 0.4) < 0.25 - 0.05 - 0.1)
    {
      MP_CHECK(own->GetValue(i) == 0);
    }
    MP_CHECK(own->GetValue(i) ==
      std::isfinite(r.Output->GetPointData()->GetArray("Linear")->GetComponent(i, 0)));
  }
  std::cout << spoiled << " NaN Source points: " << invalid << " invalid Input points" << std::endl;
  MP_CHECK(invalid > 0 && invalid < 40);
  MP_CHECK(own && LinearError(r, "Linear", own) < 1e-6);
  // The other array does not see the hole: as without any NaN.
  const Result clean = Project(target, source);
  double d = 0;
  for (vtkIdType i = 0; i < r.Output->GetNumberOfPoints(); ++i)
  {
    d = std::max(d,
      std::fabs(r.Output->GetPointData()->GetArray("Other")->GetComponent(i, 0) -
        clean.Output->GetPointData()->GetArray("Other")->GetComponent(i, 0)));
  }
  MP_CHECK(d == 0);

  // The only array projected: vtkValidPointMask is its mask.
  const Result only = Project(target, s, [](vtkMeshProjectionFilter* f) {
    f->GetPointDataArraySelection()->DisableArray("Other");
    f->GetCellDataArraySelection()->DisableArray("Density");
  });
  vtkCharArray* m = ValidMask(only, "vtkValidPointMask");
  MP_CHECK(m && !ValidMask(only, "vtkValidPointMask_Linear"));
  vtkIdType same = 0;
  for (vtkIdType i = 0; m && own && i < m->GetNumberOfValues(); ++i)
  {
    same += m->GetValue(i) == own->GetValue(i);
  }
  MP_CHECK(same == target->GetNumberOfPoints());
  return failures == 0;
}

/// Kept operators follow a hole of NaN Source values: moved, the result is
/// a fresh run's; unchanged, nothing is rebuilt.
bool CheckKeptOperatorsFollowHole(vtkUnstructuredGrid* source, vtkUnstructuredGrid* target)
{
  int failures = 0;
  vtkIdType spoiled = 0;
  auto s = WithNaNDisc(source, &spoiled);
  vtkDataArray* u = s->GetPointData()->GetArray("Linear");
  vtkNew<vtkMeshProjectionFilter> filter;
  filter->SetInputData(target);
  filter->SetSourceData(s);
  filter->Update();
  vtkNew<vtkMeshProjectionFilter> fresh;
  for (vtkIdType i = 0; i < s->GetNumberOfPoints(); ++i)
  {
    double x[3];
    s->GetPoint(i, x);
    u->SetComponent(i, 0, x[0] > 0.7 ? std::nan("") : 1 + 2 * x[0] - 3 * x[1]);
  }
  u->Modified();
  filter->Update();
  MP_CHECK(filter->GetNumberOfOperatorsBuilt() > 0);
  fresh->SetInputData(target);
  fresh->SetSourceData(Copy(s.GetPointer()));
  fresh->Update();
  vtkDataSet* a = vtkDataSet::SafeDownCast(filter->GetOutput());
  vtkDataSet* b = vtkDataSet::SafeDownCast(fresh->GetOutput());
  vtkIdType differ = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    const double va = a->GetPointData()->GetArray("Linear")->GetComponent(i, 0);
    const double vb = b->GetPointData()->GetArray("Linear")->GetComponent(i, 0);
    differ += !(va == vb || (std::isnan(va) && std::isnan(vb)) || std::fabs(va - vb) < 1e-9);
  }
  MP_CHECK(differ == 0);
  s->Modified();
  filter->Update();
  MP_CHECK(filter->GetNumberOfOperatorsBuilt() == 0);
  return failures == 0;
}

/// Cells to cells on aligned grids: NaN densities on the Source cells of
/// [0, 0.5]^2 leave exactly the Input cells there invalid; the integral
/// over the rest is conserved, intensive and extensive.
bool CheckNaNCellDensities()
{
  int failures = 0;
  auto s = mptest::Square(20, 20, true);
  auto t = mptest::Square(10, 10, true);
  vtkDataArray* density = s->GetCellData()->GetArray("Density");
  for (vtkIdType c = 0; c < s->GetNumberOfCells(); ++c)
  {
    if (c % 20 < 10 && c / 20 < 10)
    {
      density->SetComponent(c, 0, std::nan(""));
    }
  }
  for (bool extensive : { false, true })
  {
    const Result r = Project(t, s, [extensive](vtkMeshProjectionFilter* f) {
      f->GetPointDataArraySelection()->DisableArray("Linear");
      f->GetPointDataArraySelection()->DisableArray("Other");
      f->SetCellDataQuantity(
        extensive ? vtkMeshProjectionFilter::EXTENSIVE : vtkMeshProjectionFilter::INTENSIVE);
    });
    vtkDataArray* projected = r.Output->GetCellData()->GetArray("Density");
    vtkCharArray* mask =
      vtkCharArray::SafeDownCast(r.Output->GetCellData()->GetArray("vtkValidCellMask"));
    MP_CHECK(projected && mask);
    if (!projected || !mask)
    {
      continue;
    }
    vtkIdType wrong = 0;
    for (vtkIdType c = 0; c < t->GetNumberOfCells(); ++c)
    {
      const bool hole = c % 10 < 5 && c / 10 < 5;
      wrong += mask->GetValue(c) == hole || std::isfinite(projected->GetComponent(c, 0)) == hole;
    }
    MP_CHECK(wrong == 0);
    // Intensive: integral of the density; extensive: the totals' sum.
    double in = 0;
    double out = 0;
    for (vtkIdType c = 0; c < s->GetNumberOfCells(); ++c)
    {
      const double v = density->GetComponent(c, 0);
      in += std::isfinite(v) ? (extensive ? v : v / 400) : 0;
    }
    for (vtkIdType c = 0; c < t->GetNumberOfCells(); ++c)
    {
      const double v = projected->GetComponent(c, 0);
      out += std::isfinite(v) ? (extensive ? v : v / 100) : 0;
    }
    std::cout << (extensive ? "extensive" : "intensive") << ": " << in << " -> " << out
              << std::endl;
    MP_CHECK(std::fabs(in - out) < 1e-12 * std::fabs(in));
  }
  return failures == 0;
}

} // namespace

int TestMeshProjectionFilterHostile(int, char*[])
{
  int failures = 0;
  auto source = mptest::Square(24, 22);
  auto target = mptest::Square(13, 11);

  // 1. Corrupt cells, on either port, and a corrupt block of a composite Source.
  auto hexes = HexAndPolyhedron();
  const std::vector<Corruption> corruptions = Corruptions(source, hexes);
  for (const Corruption& c : corruptions)
  {
    MP_CASE(CheckCorruption(c, target, hexes));
  }
  MP_CASE(CheckCorruptBlock(source, target, corruptions[0]));
  MP_CASE(CheckShortArrays(source, target));

  // 2. NaN and infinite Source values.
  MP_CASE(CheckIsolatedNaNValues(source, target));
  MP_CASE(CheckNaNRegion(source, target));
  MP_CASE(CheckKeptOperatorsFollowHole(source, target));
  MP_CASE(CheckNaNCellDensities());
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
