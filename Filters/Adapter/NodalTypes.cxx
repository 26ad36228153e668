// SPDX-License-Identifier: BSD-3-Clause
#include "Adapter/NodalTypes.h"

#include "Geometry/NodalSplit.h"

#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkLagrangeCurve.h"
#include "vtkLagrangeHexahedron.h"
#include "vtkLagrangeQuadrilateral.h"
#include "vtkLagrangeTetra.h"
#include "vtkLagrangeTriangle.h"
#include "vtkLagrangeWedge.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkSmartPointer.h"

#include <cmath>

namespace mpvtk
{
namespace
{
/// The quadratic cells' types, per nodal type.
int QuadraticType(mp::NodalType nodal)
{
  switch (nodal)
  {
    case mp::NodalType::Edge3:
      return VTK_QUADRATIC_EDGE;
    case mp::NodalType::Triangle6:
      return VTK_QUADRATIC_TRIANGLE;
    case mp::NodalType::Quad8:
      return VTK_QUADRATIC_QUAD;
    case mp::NodalType::Quad9:
      return VTK_BIQUADRATIC_QUAD;
    case mp::NodalType::Tetra10:
      return VTK_QUADRATIC_TETRA;
    case mp::NodalType::Hexa20:
      return VTK_QUADRATIC_HEXAHEDRON;
    case mp::NodalType::Hexa27:
      return VTK_TRIQUADRATIC_HEXAHEDRON;
    case mp::NodalType::Wedge15:
      return VTK_QUADRATIC_WEDGE;
    case mp::NodalType::Wedge18:
      return VTK_BIQUADRATIC_QUADRATIC_WEDGE;
    case mp::NodalType::Pyramid13:
      return VTK_QUADRATIC_PYRAMID;
    default:
      return VTK_EMPTY_CELL;
  }
}

/// The nodal type of a Lagrange type at order 2.
mp::NodalType LagrangeNodal(int type)
{
  switch (type)
  {
    case VTK_LAGRANGE_CURVE:
      return mp::NodalType::Edge3;
    case VTK_LAGRANGE_TRIANGLE:
      return mp::NodalType::Triangle6;
    case VTK_LAGRANGE_QUADRILATERAL:
      return mp::NodalType::Quad9;
    case VTK_LAGRANGE_TETRAHEDRON:
      return mp::NodalType::Tetra10;
    case VTK_LAGRANGE_HEXAHEDRON:
      return mp::NodalType::Hexa27;
    case VTK_LAGRANGE_WEDGE:
      return mp::NodalType::Wedge18;
    default:
      return mp::NodalType::None;
  }
}

/// A Lagrange cell of order 2 of `type` (n nodes), ready to give its
/// parametric coordinates.
vtkSmartPointer<vtkCell> LagrangeCell(int type, int n)
{
  vtkSmartPointer<vtkCell> cell;
  switch (type)
  {
    case VTK_LAGRANGE_CURVE:
      cell = vtkSmartPointer<vtkLagrangeCurve>::New();
      break;
    case VTK_LAGRANGE_TRIANGLE:
      cell = vtkSmartPointer<vtkLagrangeTriangle>::New();
      break;
    case VTK_LAGRANGE_QUADRILATERAL:
      cell = vtkSmartPointer<vtkLagrangeQuadrilateral>::New();
      break;
    case VTK_LAGRANGE_TETRAHEDRON:
      cell = vtkSmartPointer<vtkLagrangeTetra>::New();
      break;
    case VTK_LAGRANGE_HEXAHEDRON:
      cell = vtkSmartPointer<vtkLagrangeHexahedron>::New();
      break;
    default:
      cell = vtkSmartPointer<vtkLagrangeWedge>::New();
      break;
  }
  cell->GetPointIds()->SetNumberOfIds(n);
  cell->GetPoints()->SetNumberOfPoints(n);
  for (int k = 0; k < n; ++k)
  {
    cell->GetPointIds()->SetId(k, k);
    cell->GetPoints()->SetPoint(k, k, 0.0, 0.0);
  }
  if (auto* quad = vtkLagrangeQuadrilateral::SafeDownCast(cell))
  {
    quad->SetOrder(2, 2);
  }
  else if (auto* hexahedron = vtkLagrangeHexahedron::SafeDownCast(cell))
  {
    hexahedron->SetOrder(2, 2, 2);
  }
  else if (auto* wedge = vtkLagrangeWedge::SafeDownCast(cell))
  {
    wedge->SetOrder(2, 2, 2, n);
  }
  else
  {
    cell->Initialize();
  }
  return cell;
}
} // namespace

bool IsAcceptedNonlinear(int type)
{
  switch (type)
  {
    case VTK_QUADRATIC_EDGE:
    case VTK_QUADRATIC_TRIANGLE:
    case VTK_QUADRATIC_QUAD:
    case VTK_BIQUADRATIC_QUAD:
    case VTK_QUADRATIC_TETRA:
    case VTK_QUADRATIC_HEXAHEDRON:
    case VTK_TRIQUADRATIC_HEXAHEDRON:
    case VTK_QUADRATIC_WEDGE:
    case VTK_BIQUADRATIC_QUADRATIC_WEDGE:
    case VTK_QUADRATIC_PYRAMID:
      return true;
    default:
      return LagrangeNodal(type) != mp::NodalType::None;
  }
}

const char* AcceptedNonlinearCells()
{
  return "Accepted second-order cells: VTK's quadratic edge, triangle, quadrilateral (8 "
         "nodes), biquadratic quadrilateral (9), tetrahedron (10), hexahedron (20), "
         "triquadratic hexahedron (27), wedge (15), biquadratic-quadratic wedge (18) and "
         "pyramid (13), and Lagrange curves, triangles, quadrilaterals, tetrahedra, hexahedra "
         "and wedges of order 2";
}

mp::NodalType NodalCellTypes::TypeOf(int type, vtkIdType npts, vtkDataSet* data, vtkIdType c)
{
  mp::NodalType nodal = LagrangeNodal(type);
  if (nodal == mp::NodalType::None)
  {
    for (int k = 1; k <= static_cast<int>(mp::NodalType::Pyramid13); ++k)
    {
      nodal = QuadraticType(mp::NodalType(k)) == type ? mp::NodalType(k) : nodal;
    }
  }
  else if (vtkDataArray* degrees = data->GetCellData()->GetHigherOrderDegrees())
  {
    // Lagrange cells may give their degrees per direction; order 2 in each.
    if (c >= degrees->GetNumberOfTuples())
    {
      return mp::NodalType::None;
    }
    for (int d = 0; d < std::min(3, degrees->GetNumberOfComponents()); ++d)
    {
      nodal = degrees->GetComponent(c, d) == 2.0 || (mp::NodalCellDimension(nodal) <= d)
        ? nodal
        : mp::NodalType::None;
    }
  }
  return nodal != mp::NodalType::None && npts == mp::NodalNodeCount(nodal) ? nodal
                                                                           : mp::NodalType::None;
}

void NodalCellTypes::Order(
  int type, mp::NodalType nodal, const vtkIdType* nodes, long long* ordered)
{
  const int n = mp::NodalNodeCount(nodal);
  const int slot = type - VTK_LAGRANGE_CURVE;
  if (slot < 0 || slot >= 6)
  {
    std::copy(nodes, nodes + n, ordered);
    return;
  }
  if (!this->Built[slot])
  {
    // Quadratic node i is the Lagrange node at the same parametric point.
    vtkNew<vtkGenericCell> quadratic;
    quadratic->SetCellType(QuadraticType(nodal));
    const double* q = quadratic->GetParametricCoords();
    const vtkSmartPointer<vtkCell> lagrange = LagrangeCell(type, n);
    const double* l = lagrange->GetParametricCoords();
    for (int i = 0; i < n; ++i)
    {
      this->Maps[slot][i] = -1;
      for (int j = 0; j < n && q && l; ++j)
      {
        const double gap = std::fabs(q[3 * i] - l[3 * j]) + std::fabs(q[3 * i + 1] - l[3 * j + 1]) +
          std::fabs(q[3 * i + 2] - l[3 * j + 2]);
        this->Maps[slot][i] = gap < 1e-9 ? j : this->Maps[slot][i];
      }
      // Not expected (both cells have the same nodes): the cell's own order.
      this->Maps[slot][i] = this->Maps[slot][i] < 0 ? i : this->Maps[slot][i];
    }
    this->Built[slot] = true;
  }
  for (int i = 0; i < n; ++i)
  {
    ordered[i] = nodes[this->Maps[slot][i]];
  }
}
} // namespace mpvtk
