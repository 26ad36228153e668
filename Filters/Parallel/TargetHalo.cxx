// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TargetHalo.cxx
 * @brief MPIParts::Halo: the fringe's ghost layer of a process's part of
 *        the target, and the hooks over its extended rows.
 *
 * The fringe's stencil of a point (FringeAggregation.h) is found in the
 * three rings of cells around it, among their points' coordinates and
 * usable flags; the serial run sees those rings whole. Here each process
 * receives the other processes' cells that can lie in those rings of its
 * own points: every cell within three longest edges of its points' box
 * (a point three rings away is at most three edges away, and so is every
 * point of a cell around a point two rings away). More cells do no harm:
 * a ring walk from a point of this part meets only cells of the whole
 * target, and all of those it meets within three rings are here.
 *
 * The ghost points become rows after this part's own (the extended rows):
 * a stencil may hold them, so P^T M P has rows there. Each extended row is
 * shared, by its global id, with every process that has it (as its own
 * point or as a ghost), and counted only where the point is counted as a
 * point of the target, so the hooks complete it like any shared row.
 */
#include "Parallel/MPIParts.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

namespace mpvtk
{
namespace
{
/// `b` grown by `margin` on every side.
Box Widened(Box b, double margin)
{
  for (int d = 0; d < 3; ++d)
  {
    b[2 * d] -= margin;
    b[2 * d + 1] += margin;
  }
  return b;
}

/// The longest edge of `mesh`'s cells.
double LongestEdge(const mp::MeshView& mesh)
{
  const int corners = mesh.CornersPerCell();
  double longest = 0.0;
  for (mp::Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const mp::CellCorners cell = mesh.Cell(c);
    for (int a = 0; a < corners; ++a)
    {
      for (int b = a + 1; b < corners; ++b)
      {
        double length2 = 0.0;
        for (int d = 0; d < 3; ++d)
        {
          const double e = mesh.Point(cell[a])[d] - mesh.Point(cell[b])[d];
          length2 += e * e;
        }
        longest = std::max(longest, length2);
      }
    }
  }
  return std::sqrt(longest);
}

/// A double's bits as a long long (messages of one type).
long long Bits(double x)
{
  long long b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

double FromBits(long long b)
{
  double x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}
} // namespace

mp::FringeHalo MPIParts::Halo(const mp::MeshView& target)
{
  // The reach: three of the longest edges of any process (a little more,
  // so that rounding in the box tests never leaves a cell out).
  double longest = LongestEdge(target);
  double all = 0.0;
  this->C->AllReduce(&longest, &all, 1, vtkCommunicator::MAX_OP);
  const double reach = mp::FringeRings * all * (1.0 + 1e-6) + 1e-300;
  Box mine = EmptyBox();
  for (mp::Index p = 0; p < target.NumberOfPoints; ++p)
  {
    Grow(mine, target.Point(p));
  }
  std::vector<double> gathered(static_cast<size_t>(6 * this->N));
  this->C->AllGather(mine.data(), gathered.data(), 6);
  std::vector<Box> boxes(static_cast<size_t>(this->N));
  for (int r = 0; r < this->N; ++r)
  {
    std::copy(gathered.begin() + 6 * r, gathered.begin() + 6 * r + 6, boxes[r].begin());
  }
  mp::FringeHalo halo;
  const std::vector<long long> ghostIds = this->ReceiveHaloCells(target, boxes, reach, halo);
  // A ghost point lies within a longest edge of the box its cell met.
  this->ShareHaloRows(target, halo, ghostIds, boxes, reach + all * (1.0 + 1e-6));
  halo.Hooks = this->HooksOver(this->HaloRows);
  return halo;
}

std::vector<long long> MPIParts::ReceiveHaloCells(
  const mp::MeshView& target, const std::vector<Box>& boxes, double reach, mp::FringeHalo& halo)
{
  const int corners = target.CornersPerCell();
  const std::vector<long long>& global = this->PointRows.RowGlobal;
  // To each process, the cells meeting its grown box: their points (global
  // id, coordinates' bits) then their corners as positions in that list.
  std::vector<std::vector<char>> out(static_cast<size_t>(this->N));
  std::vector<mp::Index> slot(static_cast<size_t>(target.NumberOfPoints), -1);
  for (int r = 0; r < this->N; ++r)
  {
    const Box reached = Widened(boxes[r], reach);
    if (r == this->Me || !Meet(reached, boxes[this->Me]))
    {
      continue;
    }
    std::vector<long long> points;
    std::vector<long long> corner;
    std::vector<mp::Index> used;
    for (mp::Index c = 0; c < target.NumberOfCells; ++c)
    {
      const mp::CellCorners cell = target.Cell(c);
      Box box = EmptyBox();
      for (int a = 0; a < corners; ++a)
      {
        Grow(box, target.Point(cell[a]));
      }
      if (!Meet(box, reached))
      {
        continue;
      }
      for (int a = 0; a < corners; ++a)
      {
        const mp::Index p = cell[a];
        if (slot[p] < 0)
        {
          slot[p] = static_cast<mp::Index>(used.size());
          used.push_back(p);
          points.push_back(global[p]);
          for (int d = 0; d < 3; ++d)
          {
            points.push_back(Bits(target.Point(p)[d]));
          }
        }
        corner.push_back(slot[p]);
      }
    }
    for (mp::Index p : used)
    {
      slot[p] = -1;
    }
    const long long head[2] = { static_cast<long long>(used.size()),
      static_cast<long long>(corner.size()) };
    Append(out[r], head, 2);
    Append(out[r], points.data(), points.size());
    Append(out[r], corner.data(), corner.size());
  }
  std::vector<std::vector<char>> in = this->AllToAll(out);
  // Each global id once: this part's point (its representative's row, as
  // the hooks combine copies there) or a ghost, numbered as first received.
  const mp::Index n = target.NumberOfPoints;
  std::unordered_map<long long, mp::Index> rowOf;
  rowOf.reserve(static_cast<size_t>(n));
  for (const std::vector<mp::Index>& copies : this->PointRows.Copies)
  {
    rowOf.emplace(global[copies[0]], copies[0]);
  }
  for (mp::Index f = 0; f < n; ++f)
  {
    rowOf.emplace(global[f], f);
  }
  std::vector<long long> ghostIds;
  for (int r = 0; r < this->N; ++r)
  {
    const std::vector<long long> v = Read<long long>(in[r]);
    if (v.size() < 2)
    {
      continue;
    }
    const size_t np = static_cast<size_t>(v[0]);
    std::vector<mp::Index> row(np);
    for (size_t k = 0; k < np; ++k)
    {
      const long long* at = v.data() + 2 + 4 * k;
      auto found = rowOf.emplace(at[0], n + static_cast<mp::Index>(ghostIds.size()));
      if (found.second)
      {
        ghostIds.push_back(at[0]);
        for (int d = 0; d < 3; ++d)
        {
          halo.Points.push_back(FromBits(at[1 + d]));
        }
      }
      row[k] = found.first->second;
    }
    const long long* corner = v.data() + 2 + 4 * np;
    for (long long k = 0; k < v[1]; ++k)
    {
      halo.Cells.push_back(row[static_cast<size_t>(corner[k])]);
    }
  }
  return ghostIds;
}

void MPIParts::ShareHaloRows(const mp::MeshView& target, const mp::FringeHalo& halo,
  const std::vector<long long>& ghostIds, const std::vector<Box>& boxes, double reach)
{
  const RowSharing& points = this->PointRows;
  const mp::Index n = target.NumberOfPoints;
  const mp::Index rows = n + halo.NumberOfPoints();
  RowSharing& state = this->HaloRows;
  state = RowSharing();
  state.Copies = points.Copies;
  state.Counted = points.Counted;
  state.Counted.resize(static_cast<size_t>(rows), 0); // a ghost row is never counted
  state.RowGlobal = points.RowGlobal;
  state.RowGlobal.insert(state.RowGlobal.end(), ghostIds.begin(), ghostIds.end());
  // The rows that stand for a point here: all but the copies after the first.
  std::vector<char> second(static_cast<size_t>(n), 0);
  for (const std::vector<mp::Index>& copies : points.Copies)
  {
    for (size_t j = 1; j < copies.size(); ++j)
    {
      second[copies[j]] = 1;
    }
  }
  std::unordered_map<long long, mp::Index> rowOf;
  rowOf.reserve(static_cast<size_t>(rows));
  for (mp::Index f = 0; f < rows; ++f)
  {
    if (f >= n || !second[f])
    {
      rowOf.emplace(state.RowGlobal[f], f);
    }
  }
  auto pointOf = [&](mp::Index f) {
    return f < n ? target.Point(f) : halo.Points.data() + 3 * (f - n);
  };
  // Every row of a process lies in its box grown by `reach`: a lower
  // process sends the global ids of its rows in there, the higher one
  // answers which it has; both then list them in that order.
  std::vector<std::vector<char>> out(static_cast<size_t>(this->N));
  std::vector<std::vector<mp::Index>> asked(static_cast<size_t>(this->N));
  Box mine = Widened(boxes[this->Me], reach);
  for (int r = this->Me + 1; r < this->N; ++r)
  {
    const Box reached = Widened(boxes[r], reach);
    if (!Meet(reached, mine))
    {
      continue;
    }
    for (mp::Index f = 0; f < rows; ++f)
    {
      if ((f >= n || !second[f]) && Inside(reached, pointOf(f)))
      {
        asked[r].push_back(f);
        Append(out[r], &state.RowGlobal[f], 1);
      }
    }
  }
  std::vector<std::vector<char>> in = this->AllToAll(out);
  std::vector<std::vector<mp::Index>> shared(static_cast<size_t>(this->N));
  std::vector<std::vector<char>> answers(static_cast<size_t>(this->N));
  for (int s = 0; s < this->Me; ++s)
  {
    for (long long id : Read<long long>(in[s]))
    {
      auto found = rowOf.find(id);
      answers[s].push_back(found != rowOf.end());
      if (found != rowOf.end())
      {
        shared[s].push_back(found->second);
      }
    }
  }
  std::vector<std::vector<char>> replies = this->AllToAll(answers);
  for (int r = this->Me + 1; r < this->N; ++r)
  {
    for (size_t i = 0; i < replies[r].size() && i < asked[r].size(); ++i)
    {
      if (replies[r][i])
      {
        shared[r].push_back(asked[r][i]);
      }
    }
  }
  for (int r = 0; r < this->N; ++r)
  {
    if (!shared[r].empty())
    {
      state.Neighbours.push_back(r);
      state.Rows.push_back(shared[r]);
      state.SharedRows.insert(state.SharedRows.end(), shared[r].begin(), shared[r].end());
    }
  }
  std::sort(state.SharedRows.begin(), state.SharedRows.end());
  state.SharedRows.erase(
    std::unique(state.SharedRows.begin(), state.SharedRows.end()), state.SharedRows.end());
}
} // namespace mpvtk
