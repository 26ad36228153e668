// SPDX-License-Identifier: BSD-3-Clause
#include "Search/CandidateLocator.h"

#include "Geometry/Predicates.h"
#include "Mesh/CellNeighbors.h"
#include "Search/SupportingFaces.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace mp
{
namespace
{
/**
 * The bounding box of cell c of `mesh` (zero beyond its SpaceDimension
 * coordinates). NaN coordinates are ignored (a box left infinite says so).
 */
void CellBox(const MeshView& mesh, Index c, double box[6])
{
  const CellCorners ids = mesh.Cell(c);
  for (int d = 0; d < 3; ++d)
  {
    box[2 * d] = std::numeric_limits<double>::infinity();
    box[2 * d + 1] = -std::numeric_limits<double>::infinity();
  }
  for (int k = 0; k < mesh.CornersPerCell(); ++k)
  {
    const double* x = mesh.Point(ids[k]);
    for (int d = 0; d < mesh.SpaceDimension; ++d)
    {
      box[2 * d] = std::min(box[2 * d], x[d]);
      box[2 * d + 1] = std::max(box[2 * d + 1], x[d]);
    }
  }
  for (int d = mesh.SpaceDimension; d < 3; ++d)
  {
    box[2 * d] = box[2 * d + 1] = 0.0;
  }
}

/**
 * CellBox for cells of `Corners` corners in `Dims` coordinates, unrolled:
 * the grid over all cells asks for every cell's box twice, and each query for
 * its candidates' boxes.
 */
template <int Corners, int Dims>
void CellBoxOf(const MeshView& mesh, Index c, double box[6])
{
  const CellCorners ids = mesh.Cell(c);
  for (int d = 0; d < 3; ++d)
  {
    box[2 * d] = std::numeric_limits<double>::infinity();
    box[2 * d + 1] = -std::numeric_limits<double>::infinity();
  }
  for (int k = 0; k < Corners; ++k)
  {
    const double* x = mesh.Point(ids[k]);
    for (int d = 0; d < Dims; ++d)
    {
      box[2 * d] = std::min(box[2 * d], x[d]);
      box[2 * d + 1] = std::max(box[2 * d + 1], x[d]);
    }
  }
  for (int d = Dims; d < 3; ++d)
  {
    box[2 * d] = box[2 * d + 1] = 0.0;
  }
}

/// CellBox for the mesh's kind of cells (segments, triangles, tetrahedra;
/// in the plane or in space): an unrolled one where there is.
void (*CellBoxFor(const MeshView& mesh))(const MeshView&, Index, double*)
{
  const int corners = mesh.CornersPerCell();
  if (mesh.SpaceDimension != 2 && mesh.SpaceDimension != 3)
  {
    return &CellBox;
  }
  const bool plane = mesh.SpaceDimension == 2;
  switch (corners)
  {
    case 2:
      return plane ? &CellBoxOf<2, 2> : &CellBoxOf<2, 3>;
    case 3:
      return plane ? &CellBoxOf<3, 2> : &CellBoxOf<3, 3>;
    case 4:
      return plane ? &CellBox : &CellBoxOf<4, 3>;
    default:
      return &CellBox;
  }
}

/**
 * Divisions of a uniform bin grid over the box [lo, hi] for `binnedCells`
 * cells of a mesh of `meshCells` cells filling it: bins about two of the
 * mesh's cells wide, at most about 8 bins per binned cell (a few boundary
 * cells in a large box), at most 4096 per axis.
 */
void BinDivisions(const double lo[3], const double hi[3], int dimension, Index meshCells,
  Index binnedCells, int divisions[3])
{
  // Bins about twice as wide as a cell of the mesh (2^d cells per bin): a
  // cell then lies in few bins (memory), and the rare queries scan few cells.
  const double n = std::max<double>(1.0, static_cast<double>(meshCells));
  double volume = 1.0;
  int used = 0;
  for (int d = 0; d < dimension; ++d)
  {
    if (hi[d] > lo[d])
    {
      volume *= hi[d] - lo[d];
      ++used;
    }
  }
  const double h = used > 0 ? 2.0 * std::pow(volume / n, 1.0 / used) : 1.0;
  for (int d = 0; d < 3; ++d)
  {
    // (written so that NaN and infinite extents give 1 bin or the cap)
    const double ratio = (hi[d] - lo[d]) / h;
    divisions[d] = d < dimension && ratio >= 1.0 ? int(std::min(4096.0, ratio)) : 1;
  }
  // Few cells in a large box (the boundary of a 3D mesh): at most about
  // 8 bins per binned cell, so that memory follows the cells, not the box.
  const double cap = 8.0 * static_cast<double>(binnedCells) + 64.0;
  while (double(divisions[0]) * divisions[1] * divisions[2] > cap)
  {
    for (int d = 0; d < 3; ++d)
    {
      divisions[d] = (divisions[d] + 1) / 2;
    }
  }
}

/**
 * Whether every cell of a mesh of `n` triangles in the plane (`cells`:
 * 3 point ids each, `points`: 3 coordinates each, `neighbors`: 3 cells or
 * -1 each) has a nonzero area and every two neighbours lie on opposite
 * sides of their shared face (no fold). Then, each cell's faces turned as
 * the cell (counter-clockwise for a positive area, clockwise for a
 * negative one), the two turns of a face between neighbours cancel, and
 * the winding number of the faces without neighbour about a point is the
 * number of cells holding it. Exact (Orient2D's signs); one pass over the
 * cells for their turns, one over their faces.
 */
template <class Id>
bool WindingCountsCells(const Id* cells, const double* points, const NeighborId* neighbors, Index n)
{
  // Bit c: cell c turns counter-clockwise (a positive area).
  std::vector<std::uint64_t> positive(static_cast<size_t>(n / 64 + 1), 0);
  Index forward = 0;
  for (Index c = 0; c < n; ++c)
  {
    const Id* ids = cells + 3 * c;
    const double area =
      Orient2D(points + 3 * Index(ids[0]), points + 3 * Index(ids[1]), points + 3 * Index(ids[2]));
    if (!(area > 0.0 || area < 0.0))
    {
      return false; // zero area (or not a number): it holds no point, its faces do not cancel
    }
    positive[static_cast<size_t>(c) / 64] |= std::uint64_t(area > 0.0) << (c % 64);
    forward += area > 0.0;
  }
  const bool alike = forward == 0 || forward == n; // every cell turns one way (the usual mesh)
  auto turnsForward = [&positive](Index c) {
    return (positive[static_cast<size_t>(c) / 64] >> (c % 64) & 1u) != 0;
  };
  for (Index c = 0; c < n; ++c)
  {
    const Id* ids = cells + 3 * c;
    for (int k = 0; k < 3; ++k)
    {
      const Index other = neighbors[3 * c + k];
      if (other <= c)
      {
        continue; // no neighbour, or the face seen from the other side
      }
      // Face k runs a -> b in c's order. Stored the other way round in the
      // neighbour's order, the two lie on opposite sides when they turn
      // alike; stored the same way, when they turn differently.
      const Id a = ids[(k + 1) % 3];
      const Id b = ids[(k + 2) % 3];
      const Id* o = cells + 3 * other;
      const bool reversed =
        (o[0] == b && o[1] == a) || (o[1] == b && o[2] == a) || (o[2] == b && o[0] == a);
      if (reversed != (alike || turnsForward(c) == turnsForward(other)))
      {
        return false; // a fold: both on one side
      }
    }
  }
  return true;
}

/// WindingCountsCells of `mesh` (triangles in the plane, with neighbours).
bool WindingCountsCells(const MeshView& mesh)
{
  return mesh.Connectivity32
    ? WindingCountsCells(mesh.Connectivity32, mesh.Points, mesh.Neighbors, mesh.NumberOfCells)
    : WindingCountsCells(mesh.Connectivity, mesh.Points, mesh.Neighbors, mesh.NumberOfCells);
}
} // namespace

BoxGridLocator::BoxGridLocator(std::shared_ptr<Shared> shared)
  : Grids(std::move(shared))
{}

std::unique_ptr<CandidateLocator> BoxGridLocator::NewForThread() const
{
  return std::unique_ptr<CandidateLocator>(new BoxGridLocator(this->Grids));
}

BoxGridLocator::BoxGridLocator(const MeshView& mesh)
  : Grids(std::make_shared<Shared>())
{
  this->Grids->Mesh = mesh;
  if (mesh.Neighbors)
  {
    std::vector<Index> boundary;
    BoundaryCells(mesh, boundary);
    this->Grids->Boundary.reset(new Bins(mesh, &boundary));
  }
}

bool BoxGridLocator::Supports(Index cell, int face) const
{
  Shared& g = *this->Grids;
  if (!g.Boundary)
  {
    return false;
  }
  // Tested on the first question (traces and fronts that never meet the
  // boundary never pay for it), by whichever thread asks first.
  std::call_once(
    g.SupportingBuilt, [&g] { g.Supporting = SupportingFaces(g.Mesh, g.Boundary->Cells); });
  const std::vector<unsigned char>& supporting = g.Supporting;
  return !supporting.empty() && (supporting[static_cast<size_t>(cell)] >> face & 1u);
}

BoxGridLocator::Bins::Bins(const MeshView& mesh, const std::vector<Index>* subset)
{
  const Index count = subset ? static_cast<Index>(subset->size()) : mesh.NumberOfCells;
  this->CellBox = CellBoxFor(mesh);
  if (subset)
  {
    this->Cells = *subset;
    this->Boxes.resize(6 * static_cast<size_t>(count));
    for (Index i = 0; i < count; ++i)
    {
      this->CellBox(mesh, this->Cells[i], &this->Boxes[6 * i]);
    }
  }
  double scratch[6];
  auto boxOf = [&](Index i) { return this->BoxOf(mesh, i, scratch); };
  double lo[3] = { 0, 0, 0 };
  double hi[3] = { 0, 0, 0 };
  bool first = true;
  for (Index i = 0; i < count; ++i)
  {
    const double* box = boxOf(i);
    for (int d = 0; d < 3; ++d)
    {
      if (!std::isfinite(box[2 * d]) || !std::isfinite(box[2 * d + 1]))
      {
        continue;
      }
      lo[d] = first ? box[2 * d] : std::min(lo[d], box[2 * d]);
      hi[d] = first ? box[2 * d + 1] : std::max(hi[d], box[2 * d + 1]);
    }
    first = false;
  }
  // The boundary cells span the mesh's bounding box (its extreme points are
  // boundary vertices), so lo/hi are the mesh's in either case.
  BinDivisions(lo, hi, mesh.SpaceDimension, mesh.NumberOfCells, count, this->Divisions);
  for (int d = 0; d < 3; ++d)
  {
    this->Origin[d] = lo[d];
    const double extent = hi[d] - lo[d];
    this->Spacing[d] = extent > 0.0 ? extent / this->Divisions[d] : 1.0;
  }
  const size_t bins = size_t(this->Divisions[0]) * this->Divisions[1] * this->Divisions[2];
  // Each cell's bins (first and last along each axis; fewer than 4097 per
  // axis) found once: the box and its range cost more than the counting
  // and the filling that read them.
  std::vector<std::int16_t> ranges(6 * static_cast<size_t>(count));
  std::vector<Index> counts(bins + 1, 0);
  auto forEachBin = [&](Index i, auto&& f) {
    const std::int16_t* r = &ranges[6 * static_cast<size_t>(i)];
    for (int k = r[2]; k <= r[5]; ++k)
      for (int j = r[1]; j <= r[4]; ++j)
        for (int i = r[0]; i <= r[3]; ++i)
          f((size_t(k) * this->Divisions[1] + j) * this->Divisions[0] + i);
  };
  for (Index i = 0; i < count; ++i)
  {
    int a[3];
    int b[3];
    this->Range(boxOf(i), a, b);
    std::int16_t* r = &ranges[6 * static_cast<size_t>(i)];
    for (int d = 0; d < 3; ++d)
    {
      r[d] = static_cast<std::int16_t>(a[d]);
      r[3 + d] = static_cast<std::int16_t>(b[d]);
    }
    forEachBin(i, [&](size_t bin) { ++counts[bin + 1]; });
  }
  for (size_t b = 0; b < bins; ++b)
  {
    counts[b + 1] += counts[b];
  }
  this->BinStart = counts;
  this->BinCells.resize(static_cast<size_t>(counts[bins]));
  for (Index i = 0; i < count; ++i)
  {
    forEachBin(i, [&](size_t bin) { this->BinCells[counts[bin]++] = i; });
  }
}

const double* BoxGridLocator::Bins::BoxOf(
  const MeshView& mesh, Index position, double scratch[6]) const
{
  if (!this->Boxes.empty())
  {
    return &this->Boxes[6 * static_cast<size_t>(position)];
  }
  this->CellBox(mesh, position, scratch);
  return scratch;
}

void BoxGridLocator::Bins::Range(const double box[6], int lo[3], int hi[3]) const
{
  for (int d = 0; d < 3; ++d)
  {
    const double a = (box[2 * d] - this->Origin[d]) / this->Spacing[d];
    const double b = (box[2 * d + 1] - this->Origin[d]) / this->Spacing[d];
    const int last = this->Divisions[d] - 1;
    // Clamp in floating point first: NaN and huge values must not overflow.
    lo[d] = (a >= 0.0) ? int(std::min<double>(a, last)) : 0;
    hi[d] = (b >= 0.0) ? int(std::min<double>(b, last)) : -1;
    if (b >= 0.0 && b < a)
    {
      hi[d] = -1;
    }
  }
}

void BoxGridLocator::FindCandidates(const double box[6], std::vector<Index>& cells)
{
  Shared& g = *this->Grids;
  std::call_once(g.AllBuilt, [&g] { g.All.reset(new Bins(g.Mesh, nullptr)); });
  this->Collect(*g.All, box, cells);
}

void BoxGridLocator::FindBoundaryCandidates(const double box[6], std::vector<Index>& cells)
{
  if (!this->Grids->Boundary)
  {
    this->FindCandidates(box, cells); // no neighbours: every cell may be at the boundary
    return;
  }
  this->Collect(*this->Grids->Boundary, box, cells);
}

bool BoxGridLocator::Outside(const double* q)
{
  Shared& g = *this->Grids;
  const MeshView& mesh = g.Mesh;
  if (!g.Boundary || mesh.CellDimension != 2 || mesh.SpaceDimension != 2 || !std::isfinite(q[0]) ||
    !std::isfinite(q[1]))
  {
    return false;
  }
  // The boundary cells whose boxes reach the ray {(x, q_y), x >= q_x}:
  // those in q's row of bins, from q's column on.
  const Bins& bins = *g.Boundary;
  const double point[6] = { q[0], q[0], q[1], q[1], 0.0, 0.0 };
  int first[3];
  int last[3];
  bins.Range(point, first, last);
  std::vector<Index>& cells = this->RayCells;
  cells.clear();
  for (int j = first[1]; j <= last[1]; ++j)
  {
    for (int i = first[0]; i < bins.Divisions[0]; ++i)
    {
      const size_t bin = size_t(j) * bins.Divisions[0] + i;
      cells.insert(cells.end(), bins.BinCells.begin() + bins.BinStart[bin],
        bins.BinCells.begin() + bins.BinStart[bin + 1]);
    }
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  // The winding number of the boundary faces about q: +1 for a face
  // crossing the ray upward in its cell's counter-clockwise turn, -1
  // downward (half-open in y: a face ending on the ray's line counts at
  // its lower end only).
  Index winding = 0;
  for (const Index position : cells)
  {
    const Index c = bins.CellOf(position);
    const CellCorners ids = mesh.Cell(c);
    const double* x[3] = { mesh.Point(ids[0]), mesh.Point(ids[1]), mesh.Point(ids[2]) };
    const double area = Orient2D(x[0], x[1], x[2]);
    if (!(area > 0.0 || area < 0.0))
    {
      return false; // zero area (or not a number): its faces bound nothing
    }
    for (int k = 0; k < 3; ++k)
    {
      if (mesh.Neighbor(c, k) >= 0)
      {
        continue;
      }
      const double* a = x[(k + 1) % 3]; // face k: the corners other than k
      const double* b = x[(k + 2) % 3];
      const bool aBelow = a[1] <= q[1];
      if (aBelow == (b[1] <= q[1]))
      {
        continue; // both ends on one side of the ray's line
      }
      // Upward (a below): the crossing is right of q when q is left of a->b.
      const double side = Orient2D(a, b, q);
      if (side == 0.0)
      {
        return false; // q on the face's line, within its span: no verdict
      }
      if (aBelow ? side > 0.0 : side < 0.0)
      {
        winding += aBelow == (area > 0.0) ? 1 : -1;
      }
    }
  }
  if (winding != 0)
  {
    return false; // held by that many cells (more than one: layers overlapping)
  }
  // Zero proves q outside only where the winding number counts cells.
  std::call_once(g.CountsBuilt, [&g] { g.WindingCounts = WindingCountsCells(g.Mesh); });
  return g.WindingCounts;
}

void BoxGridLocator::Collect(const Bins& g, const double box[6], std::vector<Index>& cells)
{
  cells.clear();
  // Only cells whose own box meets the box: bins are two cells wide, so
  // most cells in them do not, and each would cost the search a prepared
  // cell and a test. The box is grown by 1e-6 of its size: a box mapped
  // from a plane frame to space is rounded, and a cell lying in that plane
  // has no thickness.
  double size = 0.0;
  for (int d = 0; d < 3; ++d)
  {
    size = std::max(size, box[2 * d + 1] - box[2 * d]);
  }
  const double pad = 1e-6 * size;
  double lo[3];
  double hi[3];
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = box[2 * d] - pad;
    hi[d] = box[2 * d + 1] + pad;
  }
  const MeshView& mesh = this->Grids->Mesh;
  int first[3];
  int last[3];
  g.Range(box, first, last);
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i)
      {
        const size_t bin = (size_t(k) * g.Divisions[1] + j) * g.Divisions[0] + i;
        for (Index at = g.BinStart[bin]; at < g.BinStart[bin + 1]; ++at)
        {
          const Index position = g.BinCells[at];
          double scratch[6];
          const double* b = g.BoxOf(mesh, position, scratch);
          // (NaN compares false: such a cell stays)
          if (!(b[1] < lo[0] || b[0] > hi[0] || b[3] < lo[1] || b[2] > hi[1] || b[5] < lo[2] ||
                b[4] > hi[2]))
          {
            cells.push_back(g.CellOf(position));
          }
        }
      }
  // Then a cell spanning several bins once: sorting the few left costs
  // less than a mark per source cell and thread.
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
}
} // namespace mp
