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
#include <limits>
#include <map>
#include <unordered_map>

namespace mpvtk
{
vtkSmartPointer<vtkDataSet> MPIParts::ShareTarget(vtkDataSet* target)
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
  PointIndex index;
  const std::vector<PointKey> keys = this->KeyPoints(target, x, useIds, index);
  // Sent as the key's first `width` numbers.
  const size_t width = useIds ? 1 : 3;
  this->SetNeighbours(this->FindShared(x, bounds, keys, index, width), np);
  if (useIds)
  {
    this->GlobalOf.resize(static_cast<size_t>(np));
    for (vtkIdType p = 0; p < np; ++p)
    {
      this->GlobalOf[p] = static_cast<long long>(global->GetTuple1(this->Representative[p]));
    }
    return target;
  }
  return this->NumberPoints(target);
}

std::vector<PointKey> MPIParts::KeyPoints(
  vtkDataSet* target, const std::vector<double>& x, bool useIds, PointIndex& index)
{
  // Each point's identity: its global id (then the key's first number), or
  // its coordinates.
  const vtkIdType np = target->GetNumberOfPoints();
  vtkDataArray* global = target->GetPointData()->GetGlobalIds();
  std::vector<PointKey> keys(static_cast<size_t>(np));
  index.clear();
  index.reserve(static_cast<size_t>(np));
  this->Representative.resize(static_cast<size_t>(np));
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
    this->Representative[p] = index.emplace(keys[p], p).first->second;
  }
  return keys;
}

std::vector<std::vector<vtkIdType>> MPIParts::FindShared(const std::vector<double>& x,
  const Box& bounds, const std::vector<PointKey>& keys, const PointIndex& index, size_t width)
{
  const int n = this->N;
  const vtkIdType np = static_cast<vtkIdType>(keys.size());
  std::vector<double> boxes(static_cast<size_t>(6 * n));
  this->C->AllGather(bounds.data(), boxes.data(), 6);
  auto boxOf = [&](int r) {
    Box b;
    std::copy(boxes.begin() + 6 * r, boxes.begin() + 6 * r + 6, b.begin());
    return b;
  };
  // Candidates to each higher process: the points inside its box (their
  // ids, or coordinates); it answers which it has.
  std::vector<std::vector<vtkIdType>> candidates(static_cast<size_t>(n));
  std::vector<std::vector<char>> out(static_cast<size_t>(n));
  for (int r = this->Me + 1; r < n; ++r)
  {
    const Box b = boxOf(r);
    if (!Meet(b, bounds))
    {
      continue;
    }
    for (vtkIdType p = 0; p < np; ++p)
    {
      if (this->Representative[p] == p && Inside(b, &x[3 * p]))
      {
        candidates[r].push_back(p);
        Append(out[r], keys[p].X, width);
      }
    }
  }
  std::vector<std::vector<char>> in = this->AllToAll(out);
  std::vector<std::vector<vtkIdType>> shared(static_cast<size_t>(n));
  std::vector<std::vector<char>> answers(static_cast<size_t>(n));
  for (int s = 0; s < this->Me; ++s)
  {
    const std::vector<double> v = Read<double>(in[s]);
    for (size_t at = 0; at + width <= v.size(); at += width)
    {
      PointKey k{ { 0.0, 0.0, 0.0 } };
      std::copy(v.begin() + at, v.begin() + at + width, k.X);
      auto found = index.find(k);
      const char yes = found != index.end();
      answers[s].push_back(yes);
      if (yes)
      {
        shared[s].push_back(found->second);
      }
    }
  }
  std::vector<std::vector<char>> replies = this->AllToAll(answers);
  for (int r = this->Me + 1; r < n; ++r)
  {
    for (size_t i = 0; i < replies[r].size() && i < candidates[r].size(); ++i)
    {
      if (replies[r][i])
      {
        shared[r].push_back(candidates[r][i]);
      }
    }
  }
  return shared;
}

void MPIParts::SetNeighbours(const std::vector<std::vector<vtkIdType>>& shared, vtkIdType np)
{
  this->Neighbours.clear();
  this->SharedPoints.clear();
  this->Owner.assign(static_cast<size_t>(np), this->Me);
  for (int r = 0; r < this->N; ++r)
  {
    if (!shared[r].empty())
    {
      this->Neighbours.push_back(r);
      for (vtkIdType p : shared[r])
      {
        this->Owner[p] = std::min(this->Owner[p], r);
      }
      this->SharedPoints.push_back(shared[r]);
    }
  }
  for (vtkIdType p = 0; p < np; ++p)
  {
    this->Owner[p] = this->Owner[this->Representative[p]];
  }
}

vtkSmartPointer<vtkDataSet> MPIParts::NumberPoints(vtkDataSet* target)
{
  const int n = this->N;
  const vtkIdType np = target->GetNumberOfPoints();
  long long owned = 0;
  for (vtkIdType p = 0; p < np; ++p)
  {
    owned += this->Owner[p] == this->Me && this->Representative[p] == p;
  }
  std::vector<long long> counts(static_cast<size_t>(n));
  this->C->AllGather(&owned, counts.data(), 1);
  long long next = 0;
  for (int r = 0; r < this->Me; ++r)
  {
    next += counts[r];
  }
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("GlobalIds");
  ids->SetNumberOfValues(np);
  for (vtkIdType p = 0; p < np; ++p)
  {
    ids->SetValue(p,
      this->Owner[p] == this->Me && this->Representative[p] == p ? static_cast<vtkIdType>(next++) : -1);
  }
  std::vector<std::vector<double>> send(this->Neighbours.size()), recv(this->Neighbours.size());
  for (size_t i = 0; i < this->Neighbours.size(); ++i)
  {
    for (vtkIdType p : this->SharedPoints[i])
    {
      send[i].push_back(static_cast<double>(ids->GetValue(p)));
    }
    recv[i].resize(this->SharedPoints[i].size());
  }
  this->Swap(this->Neighbours, send, recv);
  for (size_t i = 0; i < this->Neighbours.size(); ++i)
  {
    if (this->Neighbours[i] > this->Me)
    {
      continue;
    }
    for (size_t k = 0; k < this->SharedPoints[i].size(); ++k)
    {
      const vtkIdType p = this->SharedPoints[i][k];
      if (this->Owner[p] == this->Neighbours[i])
      {
        ids->SetValue(p, static_cast<vtkIdType>(recv[i][k]));
      }
    }
  }
  this->GlobalOf.resize(static_cast<size_t>(np));
  for (vtkIdType p = 0; p < np; ++p)
  {
    ids->SetValue(p, ids->GetValue(this->Representative[p]));
    this->GlobalOf[p] = static_cast<long long>(ids->GetValue(p));
  }
  vtkSmartPointer<vtkDataSet> copy;
  copy.TakeReference(target->NewInstance());
  copy->ShallowCopy(target);
  copy->GetPointData()->SetGlobalIds(ids);
  return copy;
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
    std::copy(sum.begin() + s * width, sum.begin() + (s + 1) * width,
      v + rows.SharedRows[s] * width);
  }
  for (const std::vector<mp::Index>& copies : rows.Copies)
  {
    for (size_t j = 1; j < copies.size(); ++j)
    {
      std::copy(v + copies[0] * width, v + (copies[0] + 1) * width, v + copies[j] * width);
    }
  }
}

mp::SolverHooks MPIParts::Hooks(
  bool points, mp::Index rows, const std::function<vtkIdType(mp::Index)>& dataSetPoint)
{
  if (!points)
  {
    // Cells: no row is shared (BlockCG factors each part's own rows).
    mp::SolverHooks hooks;
    hooks.Reduce = [this](double* values, int count) { this->Sum(values, count); };
    return hooks;
  }
  RowSharing& state = this->PointRows;
  std::vector<mp::Index> rowOf(static_cast<size_t>(rows));
  state.Counted.assign(static_cast<size_t>(rows), 0);
  state.RowGlobal.resize(static_cast<size_t>(rows));
  for (mp::Index f = 0; f < rows; ++f)
  {
    const vtkIdType p = dataSetPoint(f);
    rowOf[static_cast<size_t>(p)] = f;
    state.RowGlobal[f] = this->GlobalOf[static_cast<size_t>(p)];
    state.Counted[f] =
      this->Owner[static_cast<size_t>(p)] == this->Me && this->Representative[static_cast<size_t>(p)] == p;
  }
  state.Copies.clear();
  {
    std::map<vtkIdType, std::vector<mp::Index>> groups;
    for (mp::Index f = 0; f < rows; ++f)
    {
      const vtkIdType p = dataSetPoint(f);
      if (this->Representative[static_cast<size_t>(p)] != p)
      {
        groups[this->Representative[static_cast<size_t>(p)]].push_back(f);
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
  state.Neighbours = this->Neighbours;
  state.Rows.assign(this->Neighbours.size(), std::vector<mp::Index>());
  state.SharedRows.clear();
  for (size_t i = 0; i < this->Neighbours.size(); ++i)
  {
    for (vtkIdType p : this->SharedPoints[i])
    {
      state.Rows[i].push_back(rowOf[static_cast<size_t>(p)]);
    }
    state.SharedRows.insert(state.SharedRows.end(), state.Rows[i].begin(), state.Rows[i].end());
  }
  std::sort(state.SharedRows.begin(), state.SharedRows.end());
  state.SharedRows.erase(
    std::unique(state.SharedRows.begin(), state.SharedRows.end()), state.SharedRows.end());
  return this->HooksOver(state);
}

mp::SolverHooks MPIParts::HooksOver(const RowSharing& rows)
{
  mp::SolverHooks hooks;
  hooks.Reduce = [this](double* values, int count) { this->Sum(values, count); };
  hooks.Counted = rows.Counted.data();
  const RowSharing* state = &rows;
  hooks.Exchange = [this, state](double* v, int width) { this->Complete(*state, v, width, false); };
  hooks.ExchangeMinimum = [this, state](double* v, int width) { this->Complete(*state, v, width, true); };
  hooks.Direct = [this, state](const mp::CsrMatrix& A, const double* B, double* X, int c,
                   const std::vector<char>& converged) {
    return this->SolveGathered(*state, A, B, X, c, converged);
  };
  return hooks;
}
} // namespace mpvtk
