// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TargetHalo.cxx
 * @brief MPIParts::Halo: the fringe's ghost layer of a process's part of
 *        the target, and the hooks over its extended rows.
 *
 * The fringe's stencil of a point (FringeAggregation.h) is found in the
 * FringeSearchRings rings of cells around it, among their points'
 * coordinates and usable flags; the serial run sees those rings whole.
 * Here each process receives the other processes' cells that can lie in
 * those rings of its own points: every cell within FringeSearchRings
 * longest edges of its points' box (a point r rings away is at most r
 * edges away, and so is every point of a cell around a point r - 1 rings
 * away). More cells do no harm: a ring walk from a point of this part
 * meets only cells of the whole target, and all of those it meets within
 * FringeSearchRings rings are here.
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

/**
 * The parents of the halo cells sent to one process, for a second-order
 * target's fringe (FringeHalo::CellParents): per cell sent, its parent's
 * place in the message's list, then per parent its type, node count and
 * nodes' global ids (a linear parent: None, no nodes).
 */
struct NodalParents
{
  std::vector<long long> Cells;   // per cell sent: its parent's place
  std::vector<long long> Parents; // type, count, global ids, per parent
  std::vector<long long> Place;   // per parent of the target: its place, or -1
  long long Count = 0;

  explicit NodalParents(const mp::MeshView& target)
    : Place(static_cast<size_t>(target.Parents()), -1)
  {}

  void Add(const mp::MeshView& target, mp::Index c, const std::vector<long long>& global)
  {
    const mp::Index p = target.ParentOf(c);
    long long& place = this->Place[static_cast<size_t>(p)];
    if (place < 0)
    {
      place = this->Count++;
      const mp::NodalType type = target.Nodal ? target.Nodal->Type[p] : mp::NodalType::None;
      const long long begin = target.Nodal ? target.Nodal->Offsets[p] : 0;
      const long long end = target.Nodal ? target.Nodal->Offsets[p + 1] : 0;
      this->Parents.push_back(static_cast<long long>(type));
      this->Parents.push_back(end - begin);
      for (long long q = begin; q < end; ++q)
      {
        this->Parents.push_back(global[static_cast<size_t>(target.Nodal->Nodes[q])]);
      }
    }
    this->Cells.push_back(place);
  }

  /// Cells' count, Cells, Parents.
  std::vector<long long> Message() const
  {
    std::vector<long long> m(1, static_cast<long long>(this->Cells.size()));
    m.insert(m.end(), this->Cells.begin(), this->Cells.end());
    m.insert(m.end(), this->Parents.begin(), this->Parents.end());
    return m;
  }
};

/**
 * The halo's parents from the messages' NodalParents (`received`, in the
 * order of the halo's cells): a parent with a node that is neither this
 * part's nor a ghost is None (no root).
 */
void ReadNodalParents(const std::vector<std::vector<long long>>& received,
  const std::unordered_map<long long, mp::Index>& rowOf, mp::FringeHalo& halo)
{
  halo.ParentOffsets.assign(1, 0);
  for (const std::vector<long long>& m : received)
  {
    const size_t cells = static_cast<size_t>(m[0]);
    const mp::Index base = static_cast<mp::Index>(halo.ParentTypes.size());
    for (size_t k = 0; k < cells; ++k)
    {
      halo.CellParents.push_back(base + static_cast<mp::Index>(m[1 + k]));
    }
    for (size_t at = 1 + cells; at < m.size();)
    {
      const long long count = m[at + 1];
      mp::NodalType type = static_cast<mp::NodalType>(m[at]);
      std::vector<long long> nodes;
      for (long long n = 0; n < count; ++n)
      {
        const auto found = rowOf.find(m[at + 2 + static_cast<size_t>(n)]);
        type = found == rowOf.end() ? mp::NodalType::None : type;
        nodes.push_back(found == rowOf.end() ? -1 : found->second);
      }
      if (type == mp::NodalType::None)
      {
        nodes.clear();
      }
      halo.ParentTypes.push_back(type);
      halo.ParentNodes.insert(halo.ParentNodes.end(), nodes.begin(), nodes.end());
      halo.ParentOffsets.push_back(static_cast<long long>(halo.ParentNodes.size()));
      at += 2 + static_cast<size_t>(count);
    }
  }
}
} // namespace

mp::FringeHalo MPIParts::Halo(const SharedTarget& shared, const mp::MeshView& target,
  const std::function<vtkIdType(mp::Index)>& dataSetPoint)
{
  // The reach: FringeSearchRings of the longest edges of any process (a
  // little more, so that rounding in the box tests never leaves a cell out).
  double longest = LongestEdge(target);
  double all = 0.0;
  this->C->AllReduce(&longest, &all, 1, vtkCommunicator::MAX_OP);
  const double reach = mp::FringeSearchRings * all * (1.0 + 1e-6) + 1e-300;
  Box mine = EmptyBox();
  for (mp::Index p = 0; p < target.NumberOfPoints; ++p)
  {
    Grow(mine, target.Point(p));
  }
  const std::vector<Box> boxes = this->GatherBoxes(mine);
  // This part's rows, as its point hooks have them (Hooks).
  const std::shared_ptr<RowSharing> points =
    this->PointRows(*shared.Points, target.NumberOfPoints, dataSetPoint);
  mp::FringeHalo halo;
  const std::vector<long long> ghostIds =
    this->ReceiveHaloCells(target, *points, boxes, reach, halo);
  // A ghost point lies within a longest edge of the box its cell met.
  halo.Hooks = this->HooksOver(
    this->ShareHaloRows(target, *points, halo, ghostIds, boxes, reach + all * (1.0 + 1e-6)));
  return halo;
}

std::vector<long long> MPIParts::ReceiveHaloCells(const mp::MeshView& target,
  const RowSharing& points, const std::vector<Box>& boxes, double reach, mp::FringeHalo& halo)
{
  const int corners = target.CornersPerCell();
  const std::vector<long long>& global = points.RowGlobal;
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
    NodalParents parents(target);
    for (mp::Index c = 0; c < target.NumberOfCells; ++c)
    {
      const mp::CellCorners cell = target.Cell(c);
      Box box = EmptyBox();
      for (int a = 0; a < corners; ++a)
      {
        Grow(box, target.Point(cell[a]));
      }
      // (A simplex of a curved cell split finer, on geometric-only points,
      // is no cell of the functions' graph the halo extends.)
      bool functions = true;
      for (int a = 0; a < corners; ++a)
      {
        functions = functions && target.HasFunction(cell[a]);
      }
      if (!functions || !Meet(box, reached))
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
      parents.Add(target, c, global);
    }
    for (mp::Index p : used)
    {
      slot[p] = -1;
    }
    const std::vector<long long> parentMessage = parents.Message();
    const long long head[3] = { static_cast<long long>(used.size()),
      static_cast<long long>(corner.size()), static_cast<long long>(parentMessage.size()) };
    Append(out[r], head, 3);
    Append(out[r], points.data(), points.size());
    Append(out[r], corner.data(), corner.size());
    Append(out[r], parentMessage.data(), parentMessage.size());
  }
  std::vector<std::vector<char>> in = this->AllToAll(out);
  // Each global id once: this part's point (its representative's row, as
  // the hooks combine copies there) or a ghost, numbered as first received.
  const mp::Index n = target.NumberOfPoints;
  std::unordered_map<long long, mp::Index> rowOf;
  rowOf.reserve(static_cast<size_t>(n));
  for (const std::vector<mp::Index>& copies : points.Copies)
  {
    rowOf.emplace(global[copies[0]], copies[0]);
  }
  for (mp::Index f = 0; f < n; ++f)
  {
    rowOf.emplace(global[f], f);
  }
  std::vector<long long> ghostIds;
  std::vector<std::vector<long long>> received; // per message, its NodalParents'
  for (int r = 0; r < this->N; ++r)
  {
    const std::vector<long long> v = Read<long long>(in[r]);
    if (v.size() < 3)
    {
      continue;
    }
    const size_t np = static_cast<size_t>(v[0]);
    std::vector<mp::Index> row(np);
    for (size_t k = 0; k < np; ++k)
    {
      const long long* at = v.data() + 3 + 4 * k;
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
    const long long* corner = v.data() + 3 + 4 * np;
    for (long long k = 0; k < v[1]; ++k)
    {
      halo.Cells.push_back(row[static_cast<size_t>(corner[k])]);
    }
    received.emplace_back(corner + v[1], corner + v[1] + v[2]);
  }
  ReadNodalParents(received, rowOf, halo);
  return ghostIds;
}

std::shared_ptr<MPIParts::RowSharing> MPIParts::ShareHaloRows(const mp::MeshView& target,
  const RowSharing& points, const mp::FringeHalo& halo, const std::vector<long long>& ghostIds,
  const std::vector<Box>& boxes, double reach)
{
  const mp::Index n = target.NumberOfPoints;
  const mp::Index rows = n + halo.NumberOfPoints();
  std::shared_ptr<RowSharing> made = std::make_shared<RowSharing>();
  RowSharing& state = *made;
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
  // Every row of a process lies in its box grown by `reach`: the rows
  // matched by their global ids among those in there (MatchRows).
  const Box mine = Widened(boxes[this->Me], reach);
  auto asks = [&](int r) {
    std::vector<mp::Index> candidates;
    const Box reached = Widened(boxes[r], reach);
    for (mp::Index f = 0; f < rows && Meet(reached, mine); ++f)
    {
      if ((f >= n || !second[f]) && Inside(reached, pointOf(f)))
      {
        candidates.push_back(f);
      }
    }
    return candidates;
  };
  auto key = [&](
               mp::Index f, char* to) { std::memcpy(to, &state.RowGlobal[f], sizeof(long long)); };
  auto find = [&](const char* from) -> mp::Index {
    long long id;
    std::memcpy(&id, from, sizeof id);
    auto found = rowOf.find(id);
    return found != rowOf.end() ? found->second : -1;
  };
  const std::vector<std::vector<mp::Index>> shared =
    this->MatchRows(sizeof(long long), asks, key, find);
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
  return made;
}
} // namespace mpvtk
