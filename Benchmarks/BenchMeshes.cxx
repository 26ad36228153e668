// SPDX-License-Identifier: BSD-3-Clause
// mesh-projection-bench's meshes: generated pairs of jittered grids, pairs
// read from .vtu files, their renumbering (--order), and their VTK copies.
#include "MeshProjectionBench.h"

#include "Mesh/SpatialOrder.h"

#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkXMLUnstructuredGridReader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <random>

namespace mpbench
{
namespace
{
/**
 * Renumbers `m`'s cells and points. "asis": unchanged (the generator's or
 * the file's numbering); "shuffled": cells and points in a random order;
 * "sorted": cells sorted into bands of about four cells' width along y,
 * by x inside a band, and points in the order the cells first use them
 * (the locality of a sweeping mesher).
 */
void Renumber(TestMesh& m, const std::string& order, unsigned seed)
{
  const int corners = m.Dimension + 1;
  const Index cells = m.NumberOfCells();
  const Index points = m.NumberOfPoints();
  if (order == "asis" || cells == 0)
  {
    return;
  }
  std::vector<Index> cellOrder(static_cast<size_t>(cells)); // new -> old
  std::iota(cellOrder.begin(), cellOrder.end(), Index(0));
  std::vector<double> x(m.Points.size());
  std::vector<Index> ids(m.Cells.size());
  if (order == "shuffled")
  {
    std::vector<Index> pointOrder(static_cast<size_t>(points)); // new -> old
    std::iota(pointOrder.begin(), pointOrder.end(), Index(0));
    std::mt19937_64 random(seed);
    std::shuffle(cellOrder.begin(), cellOrder.end(), random);
    std::shuffle(pointOrder.begin(), pointOrder.end(), random);
    std::vector<Index> newId(static_cast<size_t>(points));
    for (Index p = 0; p < points; ++p)
    {
      newId[pointOrder[p]] = p;
      std::copy_n(&m.Points[3 * pointOrder[p]], 3, &x[3 * p]);
    }
    for (Index c = 0; c < cells; ++c)
    {
      for (int k = 0; k < corners; ++k)
      {
        ids[corners * c + k] = newId[m.Cells[corners * cellOrder[c] + k]];
      }
    }
  }
  else
  {
    double lo[3] = { 1e300, 1e300, 1e300 };
    double hi[3] = { -1e300, -1e300, -1e300 };
    for (Index p = 0; p < points; ++p)
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], m.Points[3 * p + a]);
        hi[a] = std::max(hi[a], m.Points[3 * p + a]);
      }
    }
    double volume = 1;
    for (int a = 0; a < m.Dimension; ++a)
    {
      volume *= std::max(1e-300, hi[a] - lo[a]);
    }
    const double band = 4 * std::pow(volume / double(cells), 1.0 / m.Dimension);
    std::vector<std::array<double, 3>> key(static_cast<size_t>(cells));
    for (Index c = 0; c < cells; ++c)
    {
      double centre[3] = {};
      for (int k = 0; k < corners; ++k)
      {
        for (int a = 0; a < 3; ++a)
        {
          centre[a] += m.Points[3 * m.Cells[corners * c + k] + a] / corners;
        }
      }
      // 2D: bands along y, x inside; 3D: slabs along z, bands along y, x inside.
      key[c] = m.Dimension == 2
        ? std::array<double, 3>{ std::floor((centre[1] - lo[1]) / band), centre[0], 0.0 }
        : std::array<double, 3>{ std::floor((centre[2] - lo[2]) / band),
            std::floor((centre[1] - lo[1]) / band), centre[0] };
    }
    std::sort(
      cellOrder.begin(), cellOrder.end(), [&](Index a, Index b) { return key[a] < key[b]; });
    // Points in the order the sorted cells first use them: the kernel's
    // renumbering, given this cell order.
    mp::SpatialOrder sorted;
    sorted.Cells.assign(cellOrder.begin(), cellOrder.end());
    mp::RenumberMesh(m.View(false), sorted, x.data(), ids.data(), sorted.Cells.data());
  }
  m.Points.swap(x);
  m.Cells.swap(ids);
  m.Neighbors.clear();
}
/// The tetrahedra of a .vtu file, or its triangles when it has no tetrahedra.
bool ReadMesh(const std::string& name, TestMesh& m)
{
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(name.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  const vtkIdType n = grid->GetNumberOfPoints();
  m.Points.resize(static_cast<size_t>(3 * n));
  for (vtkIdType p = 0; p < n; ++p)
  {
    grid->GetPoint(p, &m.Points[3 * p]);
  }
  for (int type : { VTK_TETRA, VTK_TRIANGLE })
  {
    m.Dimension = type == VTK_TETRA ? 3 : 2;
    m.Cells.clear();
    for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
    {
      if (grid->GetCellType(c) == type)
      {
        vtkIdType count;
        const vtkIdType* ids;
        grid->GetCellPoints(c, count, ids);
        m.Cells.insert(m.Cells.end(), ids, ids + count);
      }
    }
    if (!m.Cells.empty())
    {
      return true;
    }
  }
  std::fprintf(stderr, "no triangles or tetrahedra in %s\n", name.c_str());
  return false;
}

} // namespace

/// A pair of non-matching meshes with about n target cells.
void MakePair(int dim, double n, unsigned seed, TestMesh& target, TestMesh& source)
{
  if (!TargetFile.empty())
  {
    if (!ReadMesh(TargetFile, target) || !ReadMesh(SourceFile, source))
    {
      std::exit(1);
    }
  }
  else
  {
    MakeGeneratedPair(dim, n, seed, target, source);
  }
  if (target.Dimension != source.Dimension)
  {
    std::fprintf(stderr, "the target has %d-dimensional cells, the source %d-dimensional ones\n",
      target.Dimension, source.Dimension);
    std::exit(1);
  }
  Renumber(target, Order, seed);
  Renumber(source, Order, seed + 17);
}

/// A pair of non-matching jittered grids with about n target cells.
void MakeGeneratedPair(int dim, double n, unsigned seed, TestMesh& target, TestMesh& source)
{
  if (dim == 2)
  {
    const int k = std::max(2, int(std::lround(std::sqrt(n / 2))));
    target = mptest::GridMesh(k, k, 0.25, seed);
    source = mptest::GridMesh(k + 3, k - 1, 0.25, seed + 1);
  }
  else
  {
    const int k = std::max(2, int(std::lround(std::cbrt(n / 6))));
    target = mptest::CubeMesh(k, k, k, 0.15, seed);
    source = mptest::CubeMesh(k + 1, k, k - 1, 0.15, seed + 1);
  }
}

vtkSmartPointer<vtkUnstructuredGrid> ToVTK(const TestMesh& m, const std::vector<double>* field)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkDoubleArray> coords;
  coords->SetNumberOfComponents(3);
  coords->SetNumberOfTuples(m.NumberOfPoints());
  std::copy(m.Points.begin(), m.Points.end(), coords->GetPointer(0));
  vtkNew<vtkPoints> points;
  points->SetData(coords);
  grid->SetPoints(points);
  const int corners = m.Dimension + 1;
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(m.NumberOfCells() + 1);
  for (Index c = 0; c <= m.NumberOfCells(); ++c)
  {
    offsets->SetValue(c, corners * c);
  }
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(m.Cells.size()));
  std::copy(m.Cells.begin(), m.Cells.end(), connectivity->GetPointer(0));
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  grid->SetCells(m.Dimension == 2 ? VTK_TRIANGLE : VTK_TETRA, cells);
  if (field)
  {
    vtkNew<vtkDoubleArray> u;
    u->SetName("u");
    u->SetNumberOfValues(m.NumberOfPoints());
    std::copy(field->begin(), field->end(), u->GetPointer(0));
    grid->GetPointData()->AddArray(u);
  }
  return grid;
}
} // namespace mpbench
