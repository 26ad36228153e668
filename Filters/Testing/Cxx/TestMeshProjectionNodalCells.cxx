// SPDX-License-Identifier: BSD-3-Clause
// Second-order cells seen by the adapter (Adapter/SimplexMesh.h,
// Adapter/NodalTypes.h): a mixed grid of linear, quadratic and Lagrange
// cells gives View().Nodal with each cell's type and its nodes, in the
// quadratic cell's order and in kernel point ids (also when the mesh is
// renumbered along space), and the split on those nodes fills each cell;
// a linear mesh has no Nodal; cells that are not accepted, of the wrong
// size, folded or naming a node twice are refused by name.
#include "Adapter/SimplexMesh.h"
#include "MeshProjectionTestUtilities.h"
#include "Mesh/NodalCells.h"

#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkLagrangeHexahedron.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace
{
/// Parametric coordinates of a cell type's nodes (n of them).
std::vector<double> Parametric(int type, int n)
{
  vtkNew<vtkGenericCell> cell;
  cell->SetCellType(type);
  const double* p = cell->GetParametricCoords();
  return std::vector<double>(p, p + 3 * n);
}

/// The Lagrange hexahedron of order 2's parametric coordinates.
std::vector<double> LagrangeHexahedron()
{
  vtkNew<vtkLagrangeHexahedron> cell;
  cell->GetPointIds()->SetNumberOfIds(27);
  cell->GetPoints()->SetNumberOfPoints(27);
  for (int k = 0; k < 27; ++k)
  {
    cell->GetPointIds()->SetId(k, k);
    cell->GetPoints()->SetPoint(k, 0, 0, 0);
  }
  cell->SetOrder(2, 2, 2);
  const double* p = cell->GetParametricCoords();
  return std::vector<double>(p, p + 81);
}

struct Cell
{
  int Type;
  std::vector<double> Nodes; ///< 3 coordinates per node, in the cell's own order
  double Offset;             ///< along x
};

/// A grid of the cells, each on points of its own (shifted by its offset).
vtkSmartPointer<vtkUnstructuredGrid> GridOf(const std::vector<Cell>& cells)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  grid->SetPoints(points);
  for (const Cell& cell : cells)
  {
    std::vector<vtkIdType> ids;
    for (size_t k = 0; k < cell.Nodes.size(); k += 3)
    {
      ids.push_back(
        points->InsertNextPoint(cell.Nodes[k] + cell.Offset, cell.Nodes[k + 1], cell.Nodes[k + 2]));
    }
    grid->InsertNextCell(cell.Type, static_cast<vtkIdType>(ids.size()), ids.data());
  }
  return grid;
}

double SimplexMeasure(const mp::MeshView& view, mp::Index c)
{
  const mp::CellCorners v = view.Cell(c);
  const double* a = view.Point(v[0]);
  double u[3][3];
  for (int k = 1; k < view.CornersPerCell(); ++k)
  {
    for (int d = 0; d < 3; ++d)
    {
      u[k - 1][d] = view.Point(v[k])[d] - a[d];
    }
  }
  return (u[0][0] * (u[1][1] * u[2][2] - u[1][2] * u[2][1]) -
           u[0][1] * (u[1][0] * u[2][2] - u[1][2] * u[2][0]) +
           u[0][2] * (u[1][0] * u[2][1] - u[1][1] * u[2][0])) /
    6.0;
}

/// The checks of a wrapped mixed grid (ordered or not).
bool CheckMixed(int ordering)
{
  int failures = 0;
  const std::vector<double> tetra = Parametric(VTK_QUADRATIC_TETRA, 10);
  const std::vector<double> triquadratic = Parametric(VTK_TRIQUADRATIC_HEXAHEDRON, 27);
  const std::vector<double> wedge = Parametric(VTK_QUADRATIC_WEDGE, 15);
  const std::vector<Cell> cells = { { VTK_HEXAHEDRON, Parametric(VTK_HEXAHEDRON, 8), 0.0 },
    { VTK_QUADRATIC_TETRA, tetra, 2.0 }, { VTK_LAGRANGE_HEXAHEDRON, LagrangeHexahedron(), 4.0 },
    { VTK_TRIANGLE, { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, 6.0 }, { VTK_QUADRATIC_WEDGE, wedge, 8.0 } };
  const vtkSmartPointer<vtkUnstructuredGrid> grid = GridOf(cells);
  mpvtk::SimplexMesh mesh;
  mesh.SetOrdering(ordering);
  const std::string error = mesh.Wrap(grid, "Source");
  MP_CHECK(error.empty());
  MP_CHECK(mesh.Ordered() == (ordering == mpvtk::SimplexMesh::ALWAYS));
  const mp::MeshView& view = mesh.View();
  MP_CHECK(view.Nodal != nullptr);
  if (!view.Nodal || !error.empty())
  {
    return false;
  }
  const mp::NodalCells& nodal = *view.Nodal;
  const mp::NodalType types[5] = { mp::NodalType::None, mp::NodalType::Tetra10,
    mp::NodalType::Hexa27, mp::NodalType::None, mp::NodalType::Wedge15 };
  // Each cell's nodes, in the quadratic cell's order: node i where the
  // quadratic cell's parametric point i is (the cells are their reference
  // cells, shifted).
  const std::vector<double>* order[5] = { nullptr, &tetra, &triquadratic, nullptr, &wedge };
  MP_CHECK(view.Parents() == 5 && nodal.Offsets[0] == 0);
  for (int c = 0; c < 5; ++c)
  {
    MP_CHECK(nodal.Type[c] == types[c]);
    const long long n = nodal.Offsets[c + 1] - nodal.Offsets[c];
    MP_CHECK(n == (order[c] ? static_cast<long long>(order[c]->size() / 3) : 0));
    for (long long i = 0; i < n && order[c]; ++i)
    {
      const long long node = nodal.Nodes[nodal.Offsets[c] + i];
      const double* x = view.Point(node);
      const double* want = &(*order[c])[3 * i];
      MP_CHECK(std::fabs(x[0] - want[0] - cells[c].Offset) + std::fabs(x[1] - want[1]) +
          std::fabs(x[2] - want[2]) ==
        0.0);
      // The dataset's point of that kernel point is the cell's.
      const double* y = grid->GetPoint(mesh.DataSetPoint(node));
      MP_CHECK(x[0] == y[0] && x[1] == y[1] && x[2] == y[2]);
    }
  }
  // The split: on each cell's nodes exactly, filling it.
  const double volumes[5] = { 1.0, 1.0 / 6.0, 1.0, 0.0, 0.5 };
  std::vector<double> volume(5, 0.0);
  std::vector<std::set<long long>> used(5);
  for (mp::Index s = 0; s < view.NumberOfCells; ++s)
  {
    const mp::Index p = view.ParentOf(s);
    volume[p] += SimplexMeasure(view, s);
    for (int k = 0; k < 4; ++k)
    {
      used[p].insert(view.Cell(s)[k]);
    }
  }
  for (int c = 0; c < 5; ++c)
  {
    MP_CHECK(std::fabs(volume[c] - volumes[c]) <= 1e-14);
    if (order[c])
    {
      const std::set<long long> nodes(
        nodal.Nodes + nodal.Offsets[c], nodal.Nodes + nodal.Offsets[c + 1]);
      MP_CHECK(used[c] == nodes);
    }
  }
  return failures == 0;
}

/// Wrap's error for a grid of one cell of `type` on `nodes` (ids 0..).
std::string WrapError(int type, const std::vector<double>& nodes, std::vector<vtkIdType> ids = {})
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (size_t k = 0; k < nodes.size(); k += 3)
  {
    points->InsertNextPoint(nodes[k], nodes[k + 1], nodes[k + 2]);
  }
  grid->SetPoints(points);
  if (ids.empty())
  {
    for (vtkIdType k = 0; k < points->GetNumberOfPoints(); ++k)
    {
      ids.push_back(k);
    }
  }
  grid->InsertNextCell(type, static_cast<vtkIdType>(ids.size()), ids.data());
  mpvtk::SimplexMesh mesh;
  return mesh.Wrap(grid, "Source");
}

bool Says(const std::string& text, const char* words)
{
  const bool says = text.find(words) != std::string::npos;
  if (!says)
  {
    std::cerr << "expected \"" << words << "\" in: " << text << std::endl;
  }
  return says;
}

bool CheckRefusals()
{
  int failures = 0;
  // A linear mesh has no Nodal.
  {
    mpvtk::SimplexMesh mesh;
    const vtkSmartPointer<vtkUnstructuredGrid> grid =
      GridOf({ { VTK_HEXAHEDRON, Parametric(VTK_HEXAHEDRON, 8), 0.0 } });
    MP_CHECK(mesh.Wrap(grid, "Source").empty() && mesh.View().Nodal == nullptr);
  }
  // A Lagrange hexahedron of order 3 (64 nodes).
  std::vector<double> cubic(3 * 64, 0.0);
  for (int k = 0; k < 64; ++k)
  {
    cubic[3 * k] = k % 4 / 3.0;
    cubic[3 * k + 1] = k / 4 % 4 / 3.0;
    cubic[3 * k + 2] = k / 16 / 3.0;
  }
  std::string why = WrapError(VTK_LAGRANGE_HEXAHEDRON, cubic);
  MP_CHECK(Says(why, "Source cell 0 (vtkLagrangeHexahedron) has 64 nodes") && Says(why, "order 2"));
  // A Lagrange wedge of 18 nodes is of order 2 unless its HigherOrderDegrees
  // say otherwise (1, 1, 5: 3 x 6 nodes).
  for (const bool linearTriangles : { false, true })
  {
    const vtkSmartPointer<vtkUnstructuredGrid> grid =
      GridOf({ { VTK_LAGRANGE_WEDGE, Parametric(VTK_BIQUADRATIC_QUADRATIC_WEDGE, 18), 0.0 } });
    vtkNew<vtkDoubleArray> degrees;
    degrees->SetNumberOfComponents(3);
    const double d[3] = { linearTriangles ? 1.0 : 2.0, linearTriangles ? 1.0 : 2.0,
      linearTriangles ? 5.0 : 2.0 };
    degrees->InsertNextTuple(d);
    degrees->SetName("HigherOrderDegrees");
    grid->GetCellData()->SetHigherOrderDegrees(degrees);
    mpvtk::SimplexMesh mesh;
    why = mesh.Wrap(grid, "Input");
    MP_CHECK(linearTriangles
        ? Says(why, "Input cell 0 (vtkLagrangeWedge) has 18 nodes")
        : why.empty() && mesh.View().Nodal && mesh.View().Nodal->Type[0] == mp::NodalType::Wedge18);
  }
  // Bézier cells and other nonlinear types: named, with what is accepted.
  why = WrapError(VTK_BEZIER_HEXAHEDRON, Parametric(VTK_TRIQUADRATIC_HEXAHEDRON, 27));
  MP_CHECK(Says(why, "vtkBezierHexahedron") && Says(why, "Accepted second-order cells") &&
    Says(why, "Tessellate"));
  why = WrapError(VTK_CUBIC_LINE, { 0, 0, 0, 1, 0, 0, 0.3, 0, 0, 0.6, 0, 0 });
  MP_CHECK(Says(why, "vtkCubicLine") && Says(why, "Tessellate"));
  // A quadratic tetrahedron of 9 nodes.
  std::vector<double> tetra = Parametric(VTK_QUADRATIC_TETRA, 10);
  why = WrapError(VTK_QUADRATIC_TETRA, tetra, { 0, 1, 2, 3, 4, 5, 6, 7, 8 });
  MP_CHECK(Says(why, "cell 0 has 9 points where its type needs 10"));
  // A node out of range.
  why = WrapError(VTK_QUADRATIC_TETRA, tetra, { 0, 1, 2, 3, 4, 5, 6, 7, 8, 10 });
  MP_CHECK(Says(why, "cell 0 refers to point 10"));
  // A mid node named twice (a missing mid node given as another).
  why = WrapError(VTK_QUADRATIC_TETRA, tetra, { 0, 1, 2, 3, 4, 5, 6, 7, 8, 8 });
  MP_CHECK(Says(why, "Source cell 0 (vtkQuadraticTetra) names one node twice"));
  // A mid node at a NaN point: said as such, not as a fold (nor Tessellate).
  std::vector<double> nan = tetra;
  nan[3 * 9 + 1] = std::numeric_limits<double>::quiet_NaN();
  why = WrapError(VTK_QUADRATIC_TETRA, nan);
  MP_CHECK(Says(why,
             "Source cell 0 (vtkQuadraticTetra) has a node with a NaN or infinite "
             "coordinate (point 9)") &&
    !Says(why, "folded") && !Says(why, "Tessellate"));
  // A folded quadratic tetrahedron: the mid node of edge 1-3 through the cell.
  tetra[3 * 8] = tetra[3 * 8 + 1] = tetra[3 * 8 + 2] = -0.4;
  why = WrapError(VTK_QUADRATIC_TETRA, tetra);
  MP_CHECK(Says(why, "Source cell 0 (vtkQuadraticTetra) is folded") && Says(why, "Tessellate"));
  return failures == 0;
}
} // namespace

int TestMeshProjectionNodalCells(int, char*[])
{
  int failures = 0;
  MP_CASE(CheckMixed(mpvtk::SimplexMesh::NEVER));
  MP_CASE(CheckMixed(mpvtk::SimplexMesh::ALWAYS));
  MP_CASE(CheckRefusals());
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
