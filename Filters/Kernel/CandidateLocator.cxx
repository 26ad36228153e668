// SPDX-License-Identifier: BSD-3-Clause
#include "CandidateLocator.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mp
{
namespace
{
void CellBox(const MeshView& mesh, Index c, double box[6])
{
  const Index* ids = mesh.Cell(c);
  for (int d = 0; d < 3; ++d)
  {
    box[2 * d] = std::numeric_limits<double>::infinity();
    box[2 * d + 1] = -std::numeric_limits<double>::infinity();
  }
  for (int k = 0; k < mesh.CornersPerCell(); ++k)
  {
    const double* x = mesh.Point(ids[k]);
    for (int d = 0; d < mesh.Dimension; ++d)
    {
      box[2 * d] = std::min(box[2 * d], x[d]);
      box[2 * d + 1] = std::max(box[2 * d + 1], x[d]);
    }
  }
  for (int d = mesh.Dimension; d < 3; ++d)
  {
    box[2 * d] = box[2 * d + 1] = 0.0;
  }
}
} // namespace

BoxGridLocator::BoxGridLocator(std::shared_ptr<const Bins> bins, Index cells)
  : Grid(std::move(bins))
  , Stamp(static_cast<size_t>(cells), -1)
{
}

std::unique_ptr<CandidateLocator> BoxGridLocator::NewForThread() const
{
  return std::unique_ptr<CandidateLocator>(
    new BoxGridLocator(this->Grid, static_cast<Index>(this->Stamp.size())));
}

BoxGridLocator::BoxGridLocator(const MeshView& mesh)
  : Stamp(static_cast<size_t>(mesh.NumberOfCells), -1)
{
  auto grid = std::make_shared<Bins>();
  Bins& g = *grid;
  double lo[3] = { 0, 0, 0 };
  double hi[3] = { 0, 0, 0 };
  bool first = true;
  double box[6];
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    CellBox(mesh, c, box);
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
  // Bins about twice as wide as a cell (2^d cells per bin): a cell then lies
  // in few bins (memory), and the rare queries scan few cells.
  const double n = std::max<double>(1.0, static_cast<double>(mesh.NumberOfCells));
  double volume = 1.0;
  int used = 0;
  for (int d = 0; d < mesh.Dimension; ++d)
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
    g.Origin[d] = lo[d];
    const double extent = hi[d] - lo[d];
    g.Divisions[d] =
      (d < mesh.Dimension && extent > 0.0) ? std::max(1, std::min(1 << 12, int(extent / h))) : 1;
    g.Spacing[d] = extent > 0.0 ? extent / g.Divisions[d] : 1.0;
  }
  const size_t bins = size_t(g.Divisions[0]) * g.Divisions[1] * g.Divisions[2];
  std::vector<Index> count(bins + 1, 0);
  auto forEachBin = [&](Index c, auto&& f) {
    CellBox(mesh, c, box);
    int a[3];
    int b[3];
    g.Range(box, a, b);
    for (int k = a[2]; k <= b[2]; ++k)
      for (int j = a[1]; j <= b[1]; ++j)
        for (int i = a[0]; i <= b[0]; ++i)
          f((size_t(k) * g.Divisions[1] + j) * g.Divisions[0] + i);
  };
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    forEachBin(c, [&](size_t bin) { ++count[bin + 1]; });
  }
  for (size_t b = 0; b < bins; ++b)
  {
    count[b + 1] += count[b];
  }
  g.BinStart = count;
  g.BinCells.resize(static_cast<size_t>(count[bins]));
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    forEachBin(c, [&](size_t bin) { g.BinCells[count[bin]++] = c; });
  }
  this->Grid = grid;
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
  cells.clear();
  ++this->Query;
  int lo[3];
  int hi[3];
  const Bins& g = *this->Grid;
  g.Range(box, lo, hi);
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i)
      {
        const size_t bin = (size_t(k) * g.Divisions[1] + j) * g.Divisions[0] + i;
        for (Index p = g.BinStart[bin]; p < g.BinStart[bin + 1]; ++p)
        {
          const Index c = g.BinCells[p];
          if (this->Stamp[c] != this->Query)
          {
            this->Stamp[c] = this->Query;
            cells.push_back(c);
          }
        }
      }
}
} // namespace mp
