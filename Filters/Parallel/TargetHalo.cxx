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

#include "Mesh/NodalCells.h"

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

/// Whether simplex c of `mesh` has a geometric-only corner (a simplex of a
/// curved cell split finer: MeshView::GeometricPoints).
bool IsRefined(const mp::MeshView& mesh, mp::Index c)
{
  const mp::CellCorners cell = mesh.Cell(c);
  bool refined = false;
  for (int a = 0; a < mesh.CornersPerCell(); ++a)
  {
    refined = refined || !mesh.HasFunction(cell[a]);
  }
  return refined;
}

/**
 * The longest step of a ring walk over `mesh`'s cells: the longest edge of
 * its simplices, and for a curved cell split finer (whose simplices join
 * all its nodes in one ring: ForEachFunctionPoint) the diagonal of the box
 * of its nodes and simplices' corners.
 */
double LongestEdge(const mp::MeshView& mesh)
{
  const int corners = mesh.CornersPerCell();
  double longest = 0.0;
  std::unordered_map<mp::Index, Box> refined; // per refined parent, its box
  for (mp::Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const mp::CellCorners cell = mesh.Cell(c);
    if (IsRefined(mesh, c))
    {
      Box& box = refined.emplace(mesh.ParentOf(c), EmptyBox()).first->second;
      for (int a = 0; a < corners; ++a)
      {
        Grow(box, mesh.Point(cell[a]));
      }
      mp::ForEachFunctionPoint(mesh, c, [&](mp::Index p) { Grow(box, mesh.Point(p)); });
      continue;
    }
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
  for (const auto& parent : refined)
  {
    const Box& b = parent.second;
    double length2 = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      length2 += (b[2 * d + 1] - b[2 * d]) * (b[2 * d + 1] - b[2 * d]);
    }
    longest = std::max(longest, length2);
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
 * The halo cells sent to one process: their points (global id, coordinates'
 * bits), the geometric-only points of a curved cell's finer simplices
 * (coordinates' bits: no global id, no function; the sender's bits, so
 * that the simplices are the serial ones), the cells' corners (a point's
 * place in Points, or -1 - k for geometric point k) and their parents
 * (NodalParents). A refined simplex brings all its parent's nodes, the
 * functions a ring walk meets on it (ForEachFunctionPoint).
 */
struct HaloMessage
{
  std::vector<long long> Points;    // global id, 3 coordinates' bits, per point
  std::vector<long long> Geometric; // 3 coordinates' bits per geometric point
  std::vector<long long> Corners;
  NodalParents Parents;
  std::vector<mp::Index> Used; // the target's points listed (their slots to reset)

  explicit HaloMessage(const mp::MeshView& target)
    : Parents(target)
  {}

  /// Cell c and its points, `slot` (per target point, -1 until listed)
  /// giving each point's place in this message.
  void Add(const mp::MeshView& target, mp::Index c, const std::vector<long long>& global,
    std::vector<long long>& slot)
  {
    const mp::CellCorners cell = target.Cell(c);
    bool refined = false;
    for (int a = 0; a < target.CornersPerCell(); ++a)
    {
      refined = refined || !target.HasFunction(cell[a]);
      this->Corners.push_back(this->Place(target, cell[a], global, slot));
    }
    if (refined)
    {
      mp::ForEachFunctionPoint(
        target, c, [&](mp::Index p) { this->Place(target, p, global, slot); });
    }
    this->Parents.Add(target, c, global);
  }

  /// Head (points', corners', parents' and geometric points' counts), then each list.
  void WriteTo(std::vector<char>& out) const
  {
    const std::vector<long long> parents = this->Parents.Message();
    const long long head[4] = { static_cast<long long>(this->Points.size() / 4),
      static_cast<long long>(this->Corners.size()), static_cast<long long>(parents.size()),
      static_cast<long long>(this->Geometric.size() / 3) };
    Append(out, head, 4);
    Append(out, this->Points.data(), this->Points.size());
    Append(out, this->Corners.data(), this->Corners.size());
    Append(out, parents.data(), parents.size());
    Append(out, this->Geometric.data(), this->Geometric.size());
  }

private:
  long long Place(const mp::MeshView& target, mp::Index p, const std::vector<long long>& global,
    std::vector<long long>& slot)
  {
    long long& at = slot[static_cast<size_t>(p)];
    if (at != -1)
    {
      return at;
    }
    this->Used.push_back(p);
    std::vector<long long>& list = target.HasFunction(p) ? this->Points : this->Geometric;
    at = target.HasFunction(p) ? static_cast<long long>(list.size() / 4)
                               : -1 - static_cast<long long>(list.size() / 3);
    if (target.HasFunction(p))
    {
      list.push_back(global[static_cast<size_t>(p)]);
    }
    for (int d = 0; d < 3; ++d)
    {
      list.push_back(Bits(target.Point(p)[d]));
    }
    return at;
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
  // To each process, the cells meeting its grown box (HaloMessage).
  std::vector<std::vector<char>> out(static_cast<size_t>(this->N));
  std::vector<long long> slot(static_cast<size_t>(target.AllPoints()), -1);
  for (int r = 0; r < this->N; ++r)
  {
    const Box reached = Widened(boxes[r], reach);
    if (r == this->Me || !Meet(reached, boxes[this->Me]))
    {
      continue;
    }
    HaloMessage message(target);
    for (mp::Index c = 0; c < target.NumberOfCells; ++c)
    {
      const mp::CellCorners cell = target.Cell(c);
      Box box = EmptyBox();
      for (int a = 0; a < corners; ++a)
      {
        Grow(box, target.Point(cell[a]));
      }
      if (Meet(box, reached))
      {
        message.Add(target, c, global, slot);
      }
    }
    for (mp::Index p : message.Used)
    {
      slot[static_cast<size_t>(p)] = -1;
    }
    message.WriteTo(out[r]);
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
    if (v.size() < 4)
    {
      continue;
    }
    const size_t np = static_cast<size_t>(v[0]);
    std::vector<mp::Index> row(np);
    for (size_t k = 0; k < np; ++k)
    {
      const long long* at = v.data() + 4 + 4 * k;
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
    const long long* corner = v.data() + 4 + 4 * np;
    const long long* parents = corner + v[1];
    const long long* geometric = parents + v[2];
    // (A geometric point -1 - g in Cells until the ghosts are all known.)
    const long long firstGeometric = static_cast<long long>(halo.Geometric.size() / 3);
    for (long long k = 0; k < 3 * v[3]; ++k)
    {
      halo.Geometric.push_back(FromBits(geometric[k]));
    }
    for (long long k = 0; k < v[1]; ++k)
    {
      const long long c = corner[k];
      halo.Cells.push_back(
        c >= 0 ? row[static_cast<size_t>(c)] : static_cast<mp::Index>(c - firstGeometric));
    }
    received.emplace_back(parents, geometric);
  }
  // The geometric points after the ghosts (FringeHalo::Cells).
  const mp::Index functions = n + static_cast<mp::Index>(ghostIds.size());
  for (mp::Index& k : halo.Cells)
  {
    k = k >= 0 ? k : functions + (-1 - k);
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
