// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SharedPoints.cxx
 * @brief MPIParts::ShareTarget, Hooks and Complete: the points of a target
 *        dataset that processes share, and the solver's sums over them.
 *
 * A point on the border between two processes' parts of Input is in both:
 * its row of the system is summed over them (Complete), counted once (by
 * the lowest process that has it, its Owner), and gets one value. Shared
 * points are found by their global ids when every process has usable
 * GlobalIds, else by their coordinates (the parts come from one mesh, so a
 * shared point has the same coordinates everywhere); ids are then made.
 */
#include "Parallel/MPIParts.h"

#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkIdTypeArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>
#include <unordered_map>

namespace mpvtk
{
SharedTarget MPIParts::ShareTarget(vtkDataSet* target)
{
  const vtkIdType np = target->GetNumberOfPoints();
  vtkDataArray* global = target->GetPointData()->GetGlobalIds();
  bool useIds = np == 0 ||
    (global && global->GetNumberOfComponents() == 1 && global->GetNumberOfTuples() >= np);
  this->Agree(Verdict(), &useIds);
  std::vector<double> x(static_cast<size_t>(3 * np));
  Box bounds = EmptyBox();
  for (vtkIdType p = 0; p < np; ++p)
  {
    target->GetPoint(p, &x[3 * p]);
    Grow(bounds, &x[3 * p]);
  }
  std::shared_ptr<PointSharing> points = std::make_shared<PointSharing>();
  PointIndex index;
  const std::vector<PointKey> keys = KeyPoints(target, x, useIds, index, *points);
  // Sent as the key's first `width` numbers.
  const size_t width = useIds ? 1 : 3;
  this->SetNeighbours(this->FindShared(x, bounds, keys, index, width, *points), np, *points);
  if (useIds)
  {
    points->GlobalOf.resize(static_cast<size_t>(np));
    for (vtkIdType p = 0; p < np; ++p)
    {
      points->GlobalOf[p] = static_cast<long long>(global->GetTuple1(points->Representative[p]));
    }
  }
  else
  {
    this->NumberPoints(np, *points);
  }
  SharedTarget shared;
  shared.Data = target;
  shared.Points = points;
  return shared;
}

std::vector<PointKey> MPIParts::KeyPoints(vtkDataSet* target, const std::vector<double>& x,
  bool useIds, PointIndex& index, PointSharing& points)
{
  // Each point's identity: its global id (then the key's first number), or
  // its coordinates.
  const vtkIdType np = target->GetNumberOfPoints();
  vtkDataArray* global = target->GetPointData()->GetGlobalIds();
  std::vector<PointKey> keys(static_cast<size_t>(np));
  index.clear();
  index.reserve(static_cast<size_t>(np));
  points.Representative.resize(static_cast<size_t>(np));
  for (vtkIdType p = 0; p < np; ++p)
  {
    if (useIds)
    {
      keys[p].X[0] = static_cast<double>(global->GetTuple1(p));
      keys[p].X[1] = keys[p].X[2] = 0.0;
    }
    else
    {
      keys[p] = KeyOf(&x[3 * p]);
    }
    points.Representative[p] = index.emplace(keys[p], p).first->second;
  }
  return keys;
}

std::vector<std::vector<vtkIdType>> MPIParts::FindShared(const std::vector<double>& x,
  const Box& bounds, const std::vector<PointKey>& keys, const PointIndex& index, size_t width,
  const PointSharing& points)
{
  const std::vector<Box> boxes = this->GatherBoxes(bounds);
  const vtkIdType np = static_cast<vtkIdType>(keys.size());
  // Candidates to each higher process: the points inside its box (their
  // ids, or coordinates); it answers which it has.
  auto asks = [&](int r) {
    std::vector<mp::Index> candidates;
    if (Meet(boxes[r], bounds))
    {
      for (vtkIdType p = 0; p < np; ++p)
      {
        if (points.Representative[p] == p && Inside(boxes[r], &x[3 * p]))
        {
          candidates.push_back(p);
        }
      }
    }
    return candidates;
  };
  auto key = [&](mp::Index p, char* to) { std::memcpy(to, keys[p].X, width * sizeof(double)); };
  auto find = [&](const char* from) -> mp::Index {
    PointKey k{ { 0.0, 0.0, 0.0 } };
    std::memcpy(k.X, from, width * sizeof(double));
    auto found = index.find(k);
    return found != index.end() ? found->second : -1;
  };
  const std::vector<std::vector<mp::Index>> rows =
    this->MatchRows(width * sizeof(double), asks, key, find);
  std::vector<std::vector<vtkIdType>> shared(rows.size());
  for (size_t r = 0; r < rows.size(); ++r)
  {
    shared[r].assign(rows[r].begin(), rows[r].end());
  }
  return shared;
}

void MPIParts::SetNeighbours(
  const std::vector<std::vector<vtkIdType>>& shared, vtkIdType np, PointSharing& points)
{
  points.Neighbours.clear();
  points.Shared.clear();
  points.Owner.assign(static_cast<size_t>(np), this->Me);
  for (int r = 0; r < this->N; ++r)
  {
    if (!shared[r].empty())
    {
      points.Neighbours.push_back(r);
      for (vtkIdType p : shared[r])
      {
        points.Owner[p] = std::min(points.Owner[p], r);
      }
      points.Shared.push_back(shared[r]);
    }
  }
  for (vtkIdType p = 0; p < np; ++p)
  {
    points.Owner[p] = points.Owner[points.Representative[p]];
  }
}

void MPIParts::NumberPoints(vtkIdType np, PointSharing& points)
{
  const int n = this->N;
  long long owned = 0;
  for (vtkIdType p = 0; p < np; ++p)
  {
    owned += points.Owner[p] == this->Me && points.Representative[p] == p;
  }
  std::vector<long long> counts(static_cast<size_t>(n));
  this->C->AllGather(&owned, counts.data(), 1);
  long long next = 0;
  for (int r = 0; r < this->Me; ++r)
  {
    next += counts[r];
  }
  vtkNew<vtkIdTypeArray> ids;
  ids->SetNumberOfValues(np);
  for (vtkIdType p = 0; p < np; ++p)
  {
    ids->SetValue(p,
      points.Owner[p] == this->Me && points.Representative[p] == p ? static_cast<vtkIdType>(next++)
                                                                   : -1);
  }
  std::vector<std::vector<double>> send(points.Neighbours.size()), recv(points.Neighbours.size());
  for (size_t i = 0; i < points.Neighbours.size(); ++i)
  {
    for (vtkIdType p : points.Shared[i])
    {
      send[i].push_back(static_cast<double>(ids->GetValue(p)));
    }
    recv[i].resize(points.Shared[i].size());
  }
  this->Swap(points.Neighbours, send, recv);
  for (size_t i = 0; i < points.Neighbours.size(); ++i)
  {
    if (points.Neighbours[i] > this->Me)
    {
      continue;
    }
    for (size_t k = 0; k < points.Shared[i].size(); ++k)
    {
      const vtkIdType p = points.Shared[i][k];
      if (points.Owner[p] == points.Neighbours[i])
      {
        ids->SetValue(p, static_cast<vtkIdType>(recv[i][k]));
      }
    }
  }
  points.GlobalOf.resize(static_cast<size_t>(np));
  for (vtkIdType p = 0; p < np; ++p)
  {
    ids->SetValue(p, ids->GetValue(points.Representative[p]));
    points.GlobalOf[p] = static_cast<long long>(ids->GetValue(p));
  }
}

void MPIParts::Complete(const RowSharing& rows, double* v, int width, bool minimum)
{
  auto combine = [minimum](double& into, double value) {
    into = minimum ? std::min(into, value) : into + value;
  };
  // Copies of one point here: combined into its first copy (in row order).
  for (const std::vector<mp::Index>& copies : rows.Copies)
  {
    for (size_t j = 1; j < copies.size(); ++j)
    {
      for (int c = 0; c < width; ++c)
      {
        combine(v[copies[0] * width + c], v[copies[j] * width + c]);
      }
    }
  }
  const size_t k = rows.Neighbours.size();
  std::vector<std::vector<double>> send(k), recv(k);
  for (size_t i = 0; i < k; ++i)
  {
    send[i].reserve(rows.Rows[i].size() * width);
    for (mp::Index f : rows.Rows[i])
    {
      send[i].insert(send[i].end(), v + f * width, v + (f + 1) * width);
    }
    recv[i].resize(send[i].size());
  }
  this->Swap(rows.Neighbours, send, recv);
  // Each shared row: the parts combined in the order of their processes,
  // from 0, on every process alike (the same value everywhere, bit for bit).
  std::unordered_map<mp::Index, size_t> slot;
  slot.reserve(rows.SharedRows.size());
  std::vector<double> own(rows.SharedRows.size() * width);
  std::vector<double> sum(own.size(), minimum ? std::numeric_limits<double>::infinity() : 0.0);
  for (size_t s = 0; s < rows.SharedRows.size(); ++s)
  {
    slot[rows.SharedRows[s]] = s;
    std::copy(v + rows.SharedRows[s] * width, v + (rows.SharedRows[s] + 1) * width,
      own.begin() + s * width);
  }
  bool mineAdded = false;
  auto addOwn = [&]() {
    for (size_t e = 0; e < own.size(); ++e)
    {
      combine(sum[e], own[e]);
    }
    mineAdded = true;
  };
  for (size_t i = 0; i < k; ++i)
  {
    if (!mineAdded && rows.Neighbours[i] > this->Me)
    {
      addOwn();
    }
    for (size_t j = 0; j < rows.Rows[i].size(); ++j)
    {
      const size_t s = slot[rows.Rows[i][j]];
      for (int c = 0; c < width; ++c)
      {
        combine(sum[s * width + c], recv[i][j * width + c]);
      }
    }
  }
  if (!mineAdded)
  {
    addOwn();
  }
  for (size_t s = 0; s < rows.SharedRows.size(); ++s)
  {
    std::copy(
      sum.begin() + s * width, sum.begin() + (s + 1) * width, v + rows.SharedRows[s] * width);
  }
  for (const std::vector<mp::Index>& copies : rows.Copies)
  {
    for (size_t j = 1; j < copies.size(); ++j)
    {
      std::copy(v + copies[0] * width, v + (copies[0] + 1) * width, v + copies[j] * width);
    }
  }
}

mp::SolverHooks MPIParts::Hooks(const SharedTarget& shared, bool points, mp::Index rows,
  const std::function<vtkIdType(mp::Index)>& dataSetPoint)
{
  if (!points)
  {
    // Cells: no row is shared (BlockCG factors each part's own rows).
    mp::SolverHooks hooks;
    hooks.Reduce = [this](double* values, int count) { this->Sum(values, count); };
    return hooks;
  }
  return this->HooksOver(this->PointRows(*shared.Points, rows, dataSetPoint));
}

std::shared_ptr<MPIParts::RowSharing> MPIParts::PointRows(const PointSharing& points,
  mp::Index rows, const std::function<vtkIdType(mp::Index)>& dataSetPoint) const
{
  std::shared_ptr<RowSharing> made = std::make_shared<RowSharing>();
  RowSharing& state = *made;
  std::vector<mp::Index> rowOf(static_cast<size_t>(rows));
  state.Counted.assign(static_cast<size_t>(rows), 0);
  state.RowGlobal.resize(static_cast<size_t>(rows));
  for (mp::Index f = 0; f < rows; ++f)
  {
    const vtkIdType p = dataSetPoint(f);
    rowOf[static_cast<size_t>(p)] = f;
    state.RowGlobal[f] = points.GlobalOf[static_cast<size_t>(p)];
    state.Counted[f] = points.Owner[static_cast<size_t>(p)] == this->Me &&
      points.Representative[static_cast<size_t>(p)] == p;
  }
  state.Copies.clear();
  {
    std::map<vtkIdType, std::vector<mp::Index>> groups;
    for (mp::Index f = 0; f < rows; ++f)
    {
      const vtkIdType p = dataSetPoint(f);
      if (points.Representative[static_cast<size_t>(p)] != p)
      {
        groups[points.Representative[static_cast<size_t>(p)]].push_back(f);
      }
    }
    for (auto& g : groups)
    {
      std::vector<mp::Index> rowsOf(1, rowOf[static_cast<size_t>(g.first)]);
      std::sort(g.second.begin(), g.second.end());
      rowsOf.insert(rowsOf.end(), g.second.begin(), g.second.end());
      state.Copies.push_back(rowsOf);
    }
  }
  state.Neighbours = points.Neighbours;
  state.Rows.assign(points.Neighbours.size(), std::vector<mp::Index>());
  state.SharedRows.clear();
  for (size_t i = 0; i < points.Neighbours.size(); ++i)
  {
    for (vtkIdType p : points.Shared[i])
    {
      state.Rows[i].push_back(rowOf[static_cast<size_t>(p)]);
    }
    state.SharedRows.insert(state.SharedRows.end(), state.Rows[i].begin(), state.Rows[i].end());
  }
  std::sort(state.SharedRows.begin(), state.SharedRows.end());
  state.SharedRows.erase(
    std::unique(state.SharedRows.begin(), state.SharedRows.end()), state.SharedRows.end());
  return made;
}

mp::SolverHooks MPIParts::HooksOver(std::shared_ptr<const RowSharing> rows)
{
  mp::SolverHooks hooks;
  hooks.Reduce = [this](double* values, int count) { this->Sum(values, count); };
  hooks.Counted = rows->Counted.data();
  std::shared_ptr<const RowSharing> state = std::move(rows); // (held by the hooks)
  hooks.Exchange = [this, state](double* v, int width) { this->Complete(*state, v, width, false); };
  hooks.ExchangeMinimum = [this, state](
                            double* v, int width) { this->Complete(*state, v, width, true); };
  hooks.Direct = [this, state](const mp::CsrMatrix& A, const double* B, double* X, int c,
                   const std::vector<char>& converged) {
    return this->SolveGathered(*state, A, B, X, c, converged);
  };
  return hooks;
}
} // namespace mpvtk
