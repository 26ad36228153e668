// SPDX-License-Identifier: BSD-3-Clause
#include "Adapter/DataSetChecks.h"

#include "Adapter/Threads.h"

#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkCellTypes.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkIdTypeArray.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRectilinearGrid.h"
#include "vtkStructuredGrid.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace mpvtk
{
namespace
{
/// The number of points a cell of a linear or quadratic type has (-n: at
/// least n), or 0 for a type with no fixed count worth checking (empty
/// cells, Lagrange cells: their count is their order, checked when they
/// are split).
int PointsOfType(int type)
{
  switch (type)
  {
    case VTK_VERTEX:
      return 1;
    case VTK_POLY_VERTEX:
      return -1;
    case VTK_LINE:
      return 2;
    case VTK_POLY_LINE:
      return -2;
    case VTK_TRIANGLE:
      return 3;
    case VTK_TRIANGLE_STRIP:
      return -3;
    case VTK_POLYGON:
      return -3;
    case VTK_PIXEL:
      return 4;
    case VTK_QUAD:
      return 4;
    case VTK_TETRA:
      return 4;
    case VTK_VOXEL:
      return 8;
    case VTK_HEXAHEDRON:
      return 8;
    case VTK_WEDGE:
      return 6;
    case VTK_PYRAMID:
      return 5;
    case VTK_PENTAGONAL_PRISM:
      return 10;
    case VTK_HEXAGONAL_PRISM:
      return 12;
    case VTK_POLYHEDRON:
      return -4;
    case VTK_QUADRATIC_EDGE:
      return 3;
    case VTK_QUADRATIC_TRIANGLE:
      return 6;
    case VTK_QUADRATIC_QUAD:
      return 8;
    case VTK_BIQUADRATIC_QUAD:
      return 9;
    case VTK_QUADRATIC_TETRA:
      return 10;
    case VTK_QUADRATIC_HEXAHEDRON:
      return 20;
    case VTK_TRIQUADRATIC_HEXAHEDRON:
      return 27;
    case VTK_QUADRATIC_WEDGE:
      return 15;
    case VTK_BIQUADRATIC_QUADRATIC_WEDGE:
      return 18;
    case VTK_QUADRATIC_PYRAMID:
      return 13;
    default:
      return 0;
  }
}

/// The first cell (numbered from `first`) of `cells` that reads outside
/// its arrays or names a point outside [0, numberOfPoints), as an error, or
/// an empty string. `expected(c)` gives the count a cell must have (see
/// PointsOfType; 0: any).
template <typename T, typename Expected>
std::string CheckCells(const T* offsets, vtkIdType numberOfOffsets, const T* ids,
  vtkIdType numberOfIds, vtkIdType numberOfPoints, vtkIdType first, const std::string& what,
  const Expected& expected)
{
  std::ostringstream why;
  if (numberOfOffsets == 0)
  {
    why << what << " has an empty offsets array (it needs one value more than it has cells).";
    return why.str();
  }
  const vtkIdType n = numberOfOffsets - 1;
  if (offsets[0] != 0 || offsets[n] < 0 || offsets[n] > numberOfIds)
  {
    why << what << " has offsets from " << offsets[0] << " to " << offsets[n]
        << " into a connectivity array of " << numberOfIds << " ids (they must start at 0 "
        << "and end within it).";
    return why.str();
  }
  // The first offending cell.
  const vtkIdType c = FirstWhere(n, [&](vtkIdType c) {
    const T from = offsets[c];
    const T to = offsets[c + 1];
    // (An offset past the connectivity, even one later ones come back from.)
    bool wrong = to < from || to > numberOfIds;
    const int count = expected(c);
    wrong = wrong || (count > 0 && to - from != count) || (count < 0 && to - from < -count);
    for (T i = from; i < to && !wrong; ++i)
    {
      wrong = ids[i] < 0 || ids[i] >= numberOfPoints;
    }
    return wrong;
  });
  if (c == n)
  {
    return std::string();
  }
  const T from = offsets[c];
  const T to = offsets[c + 1];
  why << what << ": cell " << first + c;
  const int count = expected(c);
  if (to < from || to > numberOfIds)
  {
    why << " has offsets " << from << " then " << to
        << " (they must not decrease nor pass the connectivity array of " << numberOfIds
        << " ids).";
  }
  else if ((count > 0 && to - from != count) || (count < 0 && to - from < -count))
  {
    why << " has " << to - from << " points where its type needs " << (count < 0 ? "at least " : "")
        << std::abs(count) << '.';
  }
  else
  {
    for (T i = from; i < to; ++i)
    {
      if (ids[i] < 0 || ids[i] >= numberOfPoints)
      {
        why << " refers to point " << ids[i] << ", which does not exist (" << numberOfPoints
            << " points).";
        break;
      }
    }
  }
  return why.str();
}

template <typename Expected>
std::string CheckCellArray(vtkCellArray* cells, vtkIdType numberOfPoints, vtkIdType first,
  const std::string& what, const Expected& expected)
{
  if (!cells)
  {
    return std::string();
  }
  if (cells->IsStorage64Bit())
  {
    vtkTypeInt64Array* o = cells->GetOffsetsArray64();
    vtkTypeInt64Array* c = cells->GetConnectivityArray64();
    return CheckCells(o->GetPointer(0), o->GetNumberOfValues(), c->GetPointer(0),
      c->GetNumberOfValues(), numberOfPoints, first, what, expected);
  }
  vtkTypeInt32Array* o = cells->GetOffsetsArray32();
  vtkTypeInt32Array* c = cells->GetConnectivityArray32();
  return CheckCells(o->GetPointer(0), o->GetNumberOfValues(), c->GetPointer(0),
    c->GetNumberOfValues(), numberOfPoints, first, what, expected);
}

/// A polyhedron's face stream: nfaces, then per face its count and ids.
std::string CheckFaceStream(vtkUnstructuredGrid* grid, vtkIdType c, const std::string& role)
{
  std::ostringstream why;
  vtkIdTypeArray* faces = grid->GetFaces();
  vtkIdTypeArray* locations = grid->GetFaceLocations();
  if (!faces || !locations || locations->GetNumberOfValues() <= c)
  {
    why << role << " cell " << c << " is a polyhedron without a face stream.";
    return why.str();
  }
  const vtkIdType size = faces->GetNumberOfValues();
  const vtkIdType* f = faces->GetPointer(0);
  vtkIdType at = locations->GetValue(c);
  if (at < 0 || at >= size)
  {
    why << role << " cell " << c << " is a polyhedron whose face stream starts at " << at
        << ", outside the faces array (" << size << " values).";
    return why.str();
  }
  const vtkIdType nfaces = f[at++];
  if (nfaces < 4)
  {
    why << role << " cell " << c << " is a polyhedron of " << nfaces
        << " faces (a closed polyhedron has at least 4).";
    return why.str();
  }
  const vtkIdType np = grid->GetNumberOfPoints();
  for (vtkIdType k = 0; k < nfaces; ++k)
  {
    const vtkIdType count = at < size ? f[at++] : -1;
    if (count < 3 || count > size - at)
    {
      why << role << " cell " << c << " is a polyhedron whose face " << k << " has "
          << (count < 0 ? std::string("no place in the faces array")
                        : std::to_string(count) + " points" +
                   (count < 3 ? " (a face needs 3)" : ", past the end of the faces array"))
          << '.';
      return why.str();
    }
    for (vtkIdType i = 0; i < count; ++i, ++at)
    {
      if (f[at] < 0 || f[at] >= np)
      {
        why << role << " cell " << c << " is a polyhedron whose face " << k << " refers to point "
            << f[at] << ", which does not exist (" << np << " points).";
        return why.str();
      }
    }
  }
  return std::string();
}
} // namespace

std::string CheckDataSet(vtkDataSet* data, const std::string& role)
{
  std::string why;
  const char* advice = " The dataset is corrupt: check the file, or the program that wrote it.";
  if (vtkPointSet* pointSet = vtkPointSet::SafeDownCast(data))
  {
    vtkPoints* points = pointSet->GetPoints();
    if (points && points->GetData()->GetNumberOfComponents() != 3)
    {
      return role + " has points of " + std::to_string(points->GetData()->GetNumberOfComponents()) +
        " components (3 are needed)." + advice;
    }
  }
  const vtkIdType np = data->GetNumberOfPoints();
  if (vtkUnstructuredGrid* grid = vtkUnstructuredGrid::SafeDownCast(data))
  {
    vtkCellArray* cells = grid->GetCells();
    const vtkIdType n = cells ? cells->GetNumberOfOffsets() - 1 : 0;
    vtkUnsignedCharArray* types = grid->GetCellTypesArray();
    if (n > 0 && (!types || types->GetNumberOfValues() != n || types->GetNumberOfComponents() != 1))
    {
      return role + " has " + std::to_string(n) + " cells but " +
        (types ? std::to_string(types->GetNumberOfValues()) : std::string("no")) + " cell types." +
        advice;
    }
    const unsigned char* t = n > 0 ? types->GetPointer(0) : nullptr;
    // The types VTK knows, once (not a name lookup per cell).
    bool known[256];
    for (int type = 0; type < 256; ++type)
    {
      known[type] = std::strcmp(vtkCellTypes::GetClassNameFromTypeId(type), "UnknownClass") != 0;
    }
    for (vtkIdType c = 0; c < n; ++c)
    {
      if (!known[t[c]])
      {
        return role + " cell " + std::to_string(c) + " has the unknown cell type " +
          std::to_string(t[c]) + "." + advice;
      }
    }
    why = CheckCellArray(cells, np, 0, role, [t](vtkIdType c) { return PointsOfType(t[c]); });
    for (vtkIdType c = 0; c < n && why.empty(); ++c)
    {
      if (t[c] == VTK_POLYHEDRON)
      {
        why = CheckFaceStream(grid, c, role);
      }
    }
  }
  else if (vtkPolyData* poly = vtkPolyData::SafeDownCast(data))
  {
    vtkCellArray* arrays[4] = { poly->GetVerts(), poly->GetLines(), poly->GetPolys(),
      poly->GetStrips() };
    const char* names[4] = { "vertices", "lines", "polygons", "triangle strips" };
    const int least[4] = { -1, -2, -3, -3 };
    vtkIdType first = 0;
    for (int k = 0; k < 4 && why.empty(); ++k)
    {
      const int count = least[k];
      why = CheckCellArray(
        arrays[k], np, first, role + "'s " + names[k], [count](vtkIdType) { return count; });
      first += arrays[k] ? std::max<vtkIdType>(arrays[k]->GetNumberOfOffsets() - 1, 0) : 0;
    }
  }
  else if (vtkStructuredGrid* structured = vtkStructuredGrid::SafeDownCast(data))
  {
    int dims[3];
    structured->GetDimensions(dims);
    const vtkIdType expected = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
    if (structured->GetNumberOfCells() > 0 && np != expected)
    {
      return role + " is a structured grid of " + std::to_string(dims[0]) + " x " +
        std::to_string(dims[1]) + " x " + std::to_string(dims[2]) + " points but holds " +
        std::to_string(np) + "." + advice;
    }
  }
  else if (vtkRectilinearGrid* rectilinear = vtkRectilinearGrid::SafeDownCast(data))
  {
    int dims[3];
    rectilinear->GetDimensions(dims);
    vtkDataArray* axes[3] = { rectilinear->GetXCoordinates(), rectilinear->GetYCoordinates(),
      rectilinear->GetZCoordinates() };
    for (int d = 0; d < 3; ++d)
    {
      if (rectilinear->GetNumberOfCells() > 0 &&
        (!axes[d] || axes[d]->GetNumberOfTuples() < dims[d]))
      {
        return role + " is a rectilinear grid of " + std::to_string(dims[d]) + " points along " +
          "xyz"[d] + " but " + (axes[d] ? std::to_string(axes[d]->GetNumberOfTuples()) : "no") +
          " coordinates." + advice;
      }
    }
  }
  if (!why.empty())
  {
    return why + advice;
  }
  // The ghost array (read here) has a value per cell; other arrays are
  // checked where they are read (Source's fields, a composite's blocks).
  vtkUnsignedCharArray* ghosts = data->GetCellGhostArray();
  if (ghosts &&
    (ghosts->GetNumberOfComponents() != 1 ||
      ghosts->GetNumberOfTuples() < data->GetNumberOfCells()))
  {
    return role + "'s cell ghost array has " + std::to_string(ghosts->GetNumberOfTuples()) +
      " tuples of " + std::to_string(ghosts->GetNumberOfComponents()) + " components for " +
      std::to_string(data->GetNumberOfCells()) + " cells (one value per cell is needed)." + advice;
  }
  return std::string();
}
} // namespace mpvtk
