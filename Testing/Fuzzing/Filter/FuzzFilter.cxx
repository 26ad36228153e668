// SPDX-License-Identifier: BSD-3-Clause
/**
 * libFuzzer harness for the whole filter: the fuzz input is decoded into an
 * Input and a Source (vtkUnstructuredGrid or vtkPolyData) with points from
 * a small lattice or any double (NaN, Inf, 1e300, 1e-300, raw bits), cells
 * of any type byte with any counts, ids, offsets, polyhedron face streams,
 * cell-type arrays of the wrong length, point and cell arrays of any values
 * and lengths, and random filter properties. Each input runs the filter
 * and checks that it returns, that nothing was read outside an array (the
 * sanitizers), and that the output is well defined:
 *  - after an error, Input passed through (same points, no projected arrays);
 *  - else every output array has a tuple per point or cell, masks are 0 or
 *    1, invalid values hold the fill value, and valid ones are finite when
 *    the Source values and coordinates were moderate.
 */
#include "vtkMeshProjectionFilter.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkCharArray.h"
#include "vtkCommand.h"
#include "vtkDataArraySelection.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace
{
/// Swallows VTK's messages (one per corrupt input would flood the log).
class QuietWindow : public vtkOutputWindow
{
public:
  static QuietWindow* New() { VTK_STANDARD_NEW_BODY(QuietWindow); }
  void DisplayText(const char*) override {}
};

/// Counts errors (the filter's and its executive's).
class ErrorCounter : public vtkCommand
{
public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long, void* text) override
  {
    if (++this->Errors == 1 && std::getenv("MP_FUZZ_STATS") && text)
    {
      const char* t = static_cast<const char*>(text);
      const char* why = std::strstr(t, "): ");
      std::fprintf(stderr, "error: %.150s\n", why ? why + 3 : t);
    }
  }
  int Errors = 0;
};

void Fail(const char* what)
{
  std::fprintf(stderr, "FuzzFilter: broken invariant: %s\n", what);
  std::abort();
}

/// Reads the fuzz input; zeros once it is used up.
struct Bytes
{
  const uint8_t* Data;
  size_t Size;
  size_t At = 0;
  bool Wild = false; ///< a value was extreme: no finiteness to expect

  uint8_t Byte() { return this->At < this->Size ? this->Data[this->At++] : 0; }
  int Small(int n) { return this->Byte() % n; }
  /// True once in n (never on the zeros past the input's end).
  bool Rare(int n) { return this->Small(n) == n - 1; }
  double Real()
  {
    const uint8_t kind = this->Byte();
    if (kind < 200)
    {
      return (kind % 9) / 4.0 - 0.5; // a lattice: meshes that meet
    }
    this->Wild = true;
    switch (kind % 6)
    {
      case 0:
        return std::numeric_limits<double>::quiet_NaN();
      case 1:
        return (kind & 1 ? -1 : 1) * std::numeric_limits<double>::infinity();
      case 2:
        return 1e300;
      case 3:
        return 1e-300;
      case 4:
        return -1e-12 * this->Byte();
      default:
      {
        uint64_t bits = 0;
        for (int k = 0; k < 8; ++k)
        {
          bits = bits << 8 | this->Byte();
        }
        double v;
        std::memcpy(&v, &bits, sizeof v);
        return v;
      }
    }
  }
  vtkIdType Id(vtkIdType points)
  {
    const uint8_t kind = this->Byte();
    if (kind < 240 || points == 0)
    {
      return points > 0 ? kind % points : 0;
    }
    switch (kind % 4)
    {
      case 0:
        return -1 - this->Byte();
      case 1:
        return points + this->Byte();
      case 2:
        return 1000000000000LL;
      default:
        return std::numeric_limits<vtkIdType>::max();
    }
  }
};

/// Cell types to draw from (any byte now and then).
const int Types[] = { VTK_TRIANGLE, VTK_TRIANGLE, VTK_QUAD, VTK_TETRA, VTK_TETRA, VTK_HEXAHEDRON,
  VTK_WEDGE, VTK_PYRAMID, VTK_POLYGON, VTK_TRIANGLE_STRIP, VTK_PIXEL, VTK_VOXEL, VTK_VERTEX,
  VTK_LINE, VTK_POLYHEDRON, VTK_QUADRATIC_TRIANGLE, VTK_EMPTY_CELL, VTK_CONVEX_POINT_SET,
  VTK_PENTAGONAL_PRISM, VTK_HEXAGONAL_PRISM };

int CountOf(int type, Bytes& in)
{
  switch (type)
  {
    case VTK_TRIANGLE:
      return 3;
    case VTK_QUAD:
    case VTK_TETRA:
    case VTK_PIXEL:
      return 4;
    case VTK_HEXAHEDRON:
    case VTK_VOXEL:
      return 8;
    case VTK_WEDGE:
      return 6;
    case VTK_PYRAMID:
      return 5;
    case VTK_VERTEX:
      return 1;
    case VTK_LINE:
      return 2;
    case VTK_QUADRATIC_TRIANGLE:
      return 6;
    case VTK_PENTAGONAL_PRISM:
      return 10;
    case VTK_HEXAGONAL_PRISM:
      return 12;
    case VTK_EMPTY_CELL:
      return 0;
    default:
      return 3 + in.Small(6);
  }
}

/// Cells into `offsets`/`connectivity`/`types` (and polyhedron faces).
void MakeCells(Bytes& in, vtkIdType points, int cells, bool anyType, vtkIdTypeArray* offsets,
  vtkIdTypeArray* connectivity, vtkUnsignedCharArray* types, vtkIdTypeArray* locations,
  vtkIdTypeArray* faces, int fixedType)
{
  offsets->InsertNextValue(0);
  for (int c = 0; c < cells; ++c)
  {
    int type = fixedType;
    if (anyType)
    {
      const uint8_t pick = in.Byte();
      type = pick < 250 ? Types[pick % (sizeof(Types) / sizeof(Types[0]))] : in.Byte();
    }
    int count = type < 0 ? 3 + in.Small(4) : CountOf(type, in);
    if (in.Rare(32))
    {
      count = in.Small(14); // the wrong number of points for its type
    }
    for (int k = 0; k < count; ++k)
    {
      connectivity->InsertNextValue(in.Id(points));
    }
    offsets->InsertNextValue(connectivity->GetNumberOfValues());
    if (types)
    {
      types->InsertNextValue(static_cast<unsigned char>(type));
    }
    if (locations)
    {
      if (type != VTK_POLYHEDRON)
      {
        locations->InsertNextValue(-1);
        continue;
      }
      locations->InsertNextValue(in.Rare(64) ? in.Id(1000) : faces->GetNumberOfValues());
      const int nfaces = 4 + in.Small(4) - (in.Rare(16) ? 4 : 0);
      faces->InsertNextValue(nfaces);
      for (int f = 0; f < nfaces; ++f)
      {
        const int n = in.Rare(16) ? in.Byte() : 3 + in.Small(2);
        faces->InsertNextValue(n);
        for (int k = 0; k < n && k < 8; ++k)
        {
          faces->InsertNextValue(in.Id(points));
        }
      }
    }
  }
  // Now and then, one offset spoiled.
  if (in.Rare(16) && offsets->GetNumberOfValues() > 0)
  {
    offsets->SetValue(in.Small(static_cast<int>(offsets->GetNumberOfValues())),
      in.Id(connectivity->GetNumberOfValues() + 1));
  }
}

void AddArrays(Bytes& in, vtkDataSet* data)
{
  for (int association = 0; association < 2; ++association)
  {
    const vtkIdType n = association == 0 ? data->GetNumberOfPoints() : data->GetNumberOfCells();
    const int arrays = in.Small(3);
    for (int a = 0; a < arrays; ++a)
    {
      vtkNew<vtkDoubleArray> array;
      array->SetName(("a" + std::to_string(a)).c_str());
      array->SetNumberOfComponents(1 + 2 * in.Small(2));
      const vtkIdType tuples = in.Rare(32) ? in.Small(8) : n;
      array->SetNumberOfTuples(tuples);
      const bool linear = !in.Rare(2);
      for (vtkIdType t = 0; t < tuples; ++t)
      {
        for (int k = 0; k < array->GetNumberOfComponents(); ++k)
        {
          array->SetComponent(t, k, linear ? 1.0 + t + k : in.Real());
        }
      }
      (association == 0 ? static_cast<vtkDataSetAttributes*>(data->GetPointData())
                        : data->GetCellData())
        ->AddArray(array);
    }
  }
}

vtkSmartPointer<vtkDataSet> MakeMesh(Bytes& in)
{
  const bool poly = in.Rare(3);
  const int dimension = 2 + in.Small(2);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const int np = in.Byte();
  for (int p = 0; p < np; ++p)
  {
    const double x = in.Real();
    const double y = in.Real();
    const double z = dimension == 3 ? in.Real() : 0.0;
    points->InsertNextPoint(x, y, z);
  }
  const int cells = in.Byte();
  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  if (poly)
  {
    vtkNew<vtkPolyData> data;
    data->SetPoints(points);
    const int kind = (2 + in.Small(4)) % 4; // polys, strips, verts, lines
    MakeCells(in, np, cells, false, offsets, connectivity, nullptr, nullptr, nullptr,
      kind == 0     ? VTK_VERTEX
        : kind == 1 ? -2
                    : -3);
    vtkNew<vtkCellArray> array;
    array->SetData(offsets, connectivity);
    if (kind == 0)
      data->SetVerts(array);
    else if (kind == 1)
      data->SetLines(array);
    else if (kind == 2)
      data->SetPolys(array);
    else
      data->SetStrips(array);
    AddArrays(in, data);
    return data;
  }
  vtkNew<vtkUnstructuredGrid> data;
  data->SetPoints(points);
  vtkNew<vtkUnsignedCharArray> types;
  vtkNew<vtkIdTypeArray> locations;
  vtkNew<vtkIdTypeArray> faces;
  const bool anyType = in.Rare(2);
  MakeCells(in, np, cells, anyType, offsets, connectivity, types, locations, faces,
    dimension == 3 ? VTK_TETRA : VTK_TRIANGLE);
  if (in.Rare(32) && types->GetNumberOfValues() > 0)
  {
    types->SetNumberOfValues(in.Small(static_cast<int>(types->GetNumberOfValues())));
  }
  vtkNew<vtkCellArray> array;
  array->SetData(offsets, connectivity);
  const bool polyhedra = faces->GetNumberOfValues() > 0;
  data->SetCells(types, array, polyhedra ? locations.GetPointer() : nullptr,
    polyhedra ? faces.GetPointer() : nullptr);
  AddArrays(in, data);
  return data;
}

/// Sets the filter's properties from the input's first four bytes (search,
/// targets, mass matrix, bounds, quantity, intersections, cache, fill, and
/// whether array a0 is projected).
void Configure(vtkMeshProjectionFilter* filter, const uint8_t properties[4])
{
  filter->SetSearchMethod(properties[0] & 1);
  filter->SetPointDataTarget(1 + (properties[0] >> 1) % 3);
  filter->SetCellDataTarget(1 + (properties[0] >> 3) % 3);
  filter->SetMassMatrix((properties[1] & 1) ? vtkMeshProjectionFilter::LUMPED_MASS
                                            : vtkMeshProjectionFilter::CONSISTENT_MASS);
  filter->SetPreserveBounds((properties[1] >> 1) & 1);
  filter->SetCellDataQuantity((properties[1] >> 2) & 1);
  filter->SetOutputIntersections((properties[1] >> 3) & 1);
  filter->SetCacheOperator((properties[1] >> 4) & 1);
  filter->SetFillWithNaN((properties[1] >> 5) & 1);
  filter->SetFillValue(-7.0);
  if (properties[2] & 1)
  {
    filter->GetPointDataArraySelection()->DisableArray("a0");
  }
}

/// Runs the filter again with the same data (kept operators), then with
/// the first value of Source's arrays a0 changed (to a value read from `in`).
void RunAgain(vtkMeshProjectionFilter* filter, vtkDataSet* source, Bytes& in)
{
  filter->Modified();
  filter->Update();
  for (int association = 0; association < 2; ++association)
  {
    vtkDataArray* a =
      source->GetAttributes(association == 0 ? vtkDataObject::POINT : vtkDataObject::CELL)
        ->GetArray("a0");
    if (a && a->GetNumberOfTuples() > 0)
    {
      a->SetComponent(0, 0, in.Real());
      a->Modified();
    }
  }
  source->Modified();
  filter->Update();
}

/// With MP_FUZZ_STATS set: how many inputs were projected, at exit (to see
/// that the decoder reaches the projection, not only the checks), and each
/// input's sizes. Counts this run (`projected`: it covered something).
void CountRun(vtkDataSet* target, vtkDataSet* source, vtkMeshProjectionFilter* filter, int errors,
  bool projected)
{
  static int runs = 0;
  static int projectedRuns = 0;
  static bool stats = std::getenv("MP_FUZZ_STATS") && std::atexit([] {
    std::fprintf(stderr, "FuzzFilter: %d of %d inputs projected\n", projectedRuns, runs);
  }) == 0;
  ++runs;
  if (stats)
  {
    std::fprintf(stderr,
      "FuzzFilter: %lld/%lld target and %lld/%lld source points/cells, covered %g, %d errors\n",
      (long long)target->GetNumberOfPoints(), (long long)target->GetNumberOfCells(),
      (long long)source->GetNumberOfPoints(), (long long)source->GetNumberOfCells(),
      filter->GetCoveredMeasure(), errors);
  }
  projectedRuns += projected;
}

/// A mask array holds only 0 and 1.
void CheckMask(vtkAbstractArray* array, vtkIdType n)
{
  vtkCharArray* m = vtkCharArray::SafeDownCast(array);
  for (vtkIdType i = 0; m && i < n; ++i)
  {
    if (m->GetValue(i) != 0 && m->GetValue(i) != 1)
    {
      Fail("a mask value other than 0 and 1");
    }
  }
}

/// CoveredFraction lies in [0, 1].
void CheckCoveredFraction(vtkAbstractArray* array, vtkIdType n)
{
  vtkDataArray* f = vtkDataArray::SafeDownCast(array);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double v = f->GetComponent(i, 0);
    if (!(v >= 0.0 && v <= 1.0))
    {
      Fail("a covered fraction outside [0, 1]");
    }
  }
}

/// A projected point array `name` where no value or coordinate was extreme:
/// valid points (in its own mask, else in `mask`) finite, invalid ones the
/// fill value.
void CheckProjectedPointValues(vtkDataSet* output, vtkAbstractArray* array, const std::string& name,
  vtkCharArray* mask, vtkMeshProjectionFilter* filter)
{
  const vtkIdType n = output->GetNumberOfPoints();
  vtkCharArray* own = vtkCharArray::SafeDownCast(
    output->GetPointData()->GetArray(("vtkValidPointMask_" + name).c_str()));
  vtkCharArray* m = own ? own : mask;
  vtkDataArray* u = vtkDataArray::SafeDownCast(array);
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int k = 0; k < u->GetNumberOfComponents(); ++k)
    {
      const double v = u->GetComponent(i, k);
      if (m->GetValue(i) ? !std::isfinite(v)
                         : !(filter->GetFillWithNaN() ? std::isnan(v) : v == -7.0))
      {
        Fail(m->GetValue(i) ? "a valid projected value is not finite"
                            : "an invalid projected value is not the fill value");
      }
    }
  }
}

/**
 * Every array of the output's point (association 0) or cell data that the
 * filter made has a tuple per point (cell), masks are 0 or 1, covered
 * fractions in [0, 1], and, when no input value was extreme (`wild` false),
 * projected point values are finite where valid and the fill value elsewhere.
 * Input's own arrays, passed through, are not looked at.
 */
void CheckOutputArrays(vtkDataSet* output, vtkDataSet* target, int association, vtkCharArray* mask,
  bool wild, vtkMeshProjectionFilter* filter)
{
  vtkDataSetAttributes* attributes =
    output->GetAttributes(association == 0 ? vtkDataObject::POINT : vtkDataObject::CELL);
  const vtkIdType n = association == 0 ? output->GetNumberOfPoints() : output->GetNumberOfCells();
  for (int a = 0; a < attributes->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = attributes->GetAbstractArray(a);
    const std::string name = array->GetName() ? array->GetName() : "";
    const bool isMask = name.rfind("vtkValid", 0) == 0;
    const bool projected = vtkDoubleArray::SafeDownCast(array) && !isMask &&
      name != "CoveredFraction" &&
      !target->GetAttributes(association == 0 ? vtkDataObject::POINT : vtkDataObject::CELL)
         ->GetAbstractArray(name.c_str());
    if (!projected && !isMask && name != "CoveredFraction")
    {
      continue; // Input's own arrays, passed through as they were
    }
    if (array->GetNumberOfTuples() != n)
    {
      Fail("an output array does not have a tuple per point or cell");
    }
    if (isMask)
    {
      CheckMask(array, n);
    }
    else if (name == "CoveredFraction")
    {
      CheckCoveredFraction(array, n);
    }
    else if (association == 0 && !wild)
    {
      CheckProjectedPointValues(output, array, name, mask, filter);
    }
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static bool once = [] {
    vtkNew<QuietWindow> quiet;
    vtkOutputWindow::SetInstance(quiet);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    return true;
  }();
  (void)once;
  Bytes in{ data, size };
  const uint8_t properties[4] = { in.Byte(), in.Byte(), in.Byte(), in.Byte() };
  vtkSmartPointer<vtkDataSet> target = MakeMesh(in);
  vtkSmartPointer<vtkDataSet> source = MakeMesh(in);

  vtkNew<vtkMeshProjectionFilter> filter;
  vtkNew<ErrorCounter> errors;
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->SetInputData(target);
  filter->SetSourceData(source);
  Configure(filter, properties);
  filter->Update();
  if (properties[3] & 1)
  {
    RunAgain(filter, source, in);
  }

  vtkDataSet* output = vtkDataSet::SafeDownCast(filter->GetOutput());
  if (!output || output->GetNumberOfPoints() != target->GetNumberOfPoints() ||
    output->GetNumberOfCells() != target->GetNumberOfCells())
  {
    Fail("the output is not Input's shape");
  }
  vtkCharArray* mask =
    vtkCharArray::SafeDownCast(output->GetPointData()->GetArray("vtkValidPointMask"));
  CountRun(target, source, filter, errors->Errors, mask && filter->GetCoveredMeasure() > 0);
  if (!mask)
  {
    return 0; // Input passed through (an error, or nothing to project with)
  }
  for (int association = 0; association < 2; ++association)
  {
    CheckOutputArrays(output, target, association, mask, in.Wild, filter);
  }
  return 0;
}
