// SPDX-License-Identifier: BSD-3-Clause
#include "Parallel/MPIParts.h"

#include "vtkCommunicator.h"
#include "vtkMPI.h"
#include "vtkMPICommunicator.h"
#include "vtkMultiProcessController.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <string>
#include <utility>

namespace mpvtk
{
MPIParts::MPIParts(vtkMultiProcessController* controller)
  : C(controller)
  , Mpi(vtkMPICommunicator::SafeDownCast(controller->GetCommunicator()))
  , Me(controller->GetLocalProcessId())
  , N(controller->GetNumberOfProcesses())
{}

Verdict MPIParts::Agree(const Verdict& verdict, bool* flag)
{
  const bool done = verdict.Ok();
  int mine[2] = { done ? this->N : this->Me, flag ? (*flag ? 1 : 0) : 1 };
  int all[2] = { 0, 0 };
  this->C->AllReduce(mine, all, 2, vtkCommunicator::MIN_OP);
  if (flag)
  {
    *flag = all[1] != 0;
  }
  const int first = all[0];
  if (first >= this->N)
  {
    return Verdict();
  }
  // The first process's outcome, reason and origin, to the others.
  std::string text = first == this->Me ? verdict.Why : std::string();
  long long head[3] = { static_cast<long long>(verdict.What), static_cast<long long>(text.size()),
    verdict.Process < 0 ? first : verdict.Process };
  this->C->Broadcast(head, 3, first);
  text.resize(static_cast<size_t>(head[1]));
  if (head[1] > 0)
  {
    this->C->Broadcast(&text[0], head[1], first);
  }
  return { static_cast<Outcome>(head[0]), text, static_cast<int>(head[2]) };
}

void MPIParts::Abandon(const std::string& why)
{
  std::cerr << "MeshProjection: " << why << " (on process " << this->Me
            << "): the other processes may be waiting in a collective step, so the run is "
               "aborted on every process."
            << std::endl;
  MPI_Abort(*this->Mpi->GetMPIComm()->GetHandle(), 1);
}

void MPIParts::Or(std::vector<char>& flags)
{
  std::vector<int> mine(flags.begin(), flags.end()), all(flags.size());
  if (!flags.empty())
  {
    this->C->AllReduce(
      mine.data(), all.data(), static_cast<vtkIdType>(mine.size()), vtkCommunicator::MAX_OP);
  }
  for (size_t i = 0; i < flags.size(); ++i)
  {
    flags[i] = all[i] != 0;
  }
}

void MPIParts::Sum(double* values, int count)
{
  if (count <= 0)
  {
    return;
  }
  std::vector<double> mine(values, values + count);
  this->C->AllReduce(mine.data(), values, count, vtkCommunicator::SUM_OP);
}

void MPIParts::Minimum(double* values, int count)
{
  if (count <= 0)
  {
    return;
  }
  std::vector<double> mine(values, values + count);
  this->C->AllReduce(mine.data(), values, count, vtkCommunicator::MIN_OP);
}

std::vector<unsigned int> MPIParts::Union(const std::vector<unsigned int>& values)
{
  std::vector<std::vector<char>> out(static_cast<size_t>(this->N));
  for (int r = 0; r < this->N; ++r)
  {
    Append(out[r], values.data(), values.size());
  }
  std::vector<unsigned int> all;
  for (const std::vector<char>& in : this->AllToAll(out))
  {
    const std::vector<unsigned int> v = Read<unsigned int>(in);
    all.insert(all.end(), v.begin(), v.end());
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

std::vector<double> MPIParts::UnionOfValues(const std::vector<double>& values)
{
  std::vector<std::vector<char>> out(static_cast<size_t>(this->N));
  const std::vector<double> mine = SortedValues(values);
  for (int r = 0; r < this->N; ++r)
  {
    Append(out[r], mine.data(), mine.size());
  }
  std::vector<double> all;
  for (const std::vector<char>& in : this->AllToAll(out))
  {
    const std::vector<double> v = Read<double>(in);
    all.insert(all.end(), v.begin(), v.end());
  }
  return SortedValues(all);
}

std::vector<double> MPIParts::SumByKey(
  const std::vector<long long>& keys, int width, const std::vector<double>& values)
{
  // Each entry goes to the process its key hashes to, which sums the
  // entries of each key and answers every entry, in the order received.
  const int n = this->N;
  const size_t w = static_cast<size_t>(width);
  std::vector<std::vector<char>> out(static_cast<size_t>(n));
  std::vector<std::vector<size_t>> sent(static_cast<size_t>(n));
  for (size_t i = 0; i < values.size(); ++i)
  {
    const std::uint64_t h = mp::Fnv1a64(keys.data() + w * i, w * sizeof(long long));
    const size_t r = static_cast<size_t>((h ^ (h >> 29)) % static_cast<std::uint64_t>(n));
    long long bits;
    std::memcpy(&bits, &values[i], sizeof(bits));
    Append(out[r], keys.data() + w * i, w);
    Append(out[r], &bits, 1);
    sent[r].push_back(i);
  }
  std::vector<std::vector<char>> in = this->AllToAll(out);
  // Received entries (process, position), sorted by key: runs of one key.
  std::vector<std::vector<long long>> got(static_cast<size_t>(n));
  std::vector<std::pair<int, size_t>> order;
  for (int r = 0; r < n; ++r)
  {
    got[r] = Read<long long>(in[r]);
    for (size_t j = 0; j < got[r].size() / (w + 1); ++j)
    {
      order.emplace_back(r, j);
    }
  }
  auto keyOf = [&](const std::pair<int, size_t>& e) {
    return got[e.first].data() + (w + 1) * e.second;
  };
  std::sort(order.begin(), order.end(),
    [&](const std::pair<int, size_t>& a, const std::pair<int, size_t>& b) {
      const long long* x = keyOf(a);
      const long long* y = keyOf(b);
      return std::lexicographical_compare(x, x + w, y, y + w) || (std::equal(x, x + w, y) && a < b);
    });
  std::vector<std::vector<double>> answer(static_cast<size_t>(n));
  for (int r = 0; r < n; ++r)
  {
    answer[r].resize(got[r].size() / (w + 1));
  }
  for (size_t a = 0; a < order.size();)
  {
    size_t b = a;
    double total = 0.0;
    for (; b < order.size() && std::equal(keyOf(order[a]), keyOf(order[a]) + w, keyOf(order[b]));
         ++b)
    {
      double v;
      std::memcpy(&v, keyOf(order[b]) + w, sizeof(v));
      total += v; // in (process, position) order: the same on any run
    }
    for (; a < b; ++a)
    {
      answer[order[a].first][order[a].second] = total;
    }
  }
  for (int r = 0; r < n; ++r)
  {
    out[r].clear();
    Append(out[r], answer[r].data(), answer[r].size());
  }
  in = this->AllToAll(out);
  std::vector<double> sums(values.size(), 0.0);
  for (int r = 0; r < n; ++r)
  {
    const std::vector<double> back = Read<double>(in[r]);
    for (size_t j = 0; j < back.size() && j < sent[r].size(); ++j)
    {
      sums[sent[r][j]] = back[j];
    }
  }
  return sums;
}

std::vector<std::vector<char>> MPIParts::AllToAll(std::vector<std::vector<char>>& out)
{
  const int n = this->N;
  std::vector<long long> sizes(static_cast<size_t>(n)), all(static_cast<size_t>(n) * n);
  for (int r = 0; r < n; ++r)
  {
    sizes[r] = static_cast<long long>(out[r].size());
  }
  this->C->AllGather(sizes.data(), all.data(), n);
  std::vector<std::vector<char>> in(static_cast<size_t>(n));
  in[this->Me].swap(out[this->Me]);
  // Messages in chunks below 2^31 bytes (MPI counts are ints).
  const long long chunk = 1LL << 30;
  size_t count = 0;
  for (int r = 0; r < n; ++r)
  {
    if (r != this->Me)
    {
      in[r].resize(static_cast<size_t>(all[static_cast<size_t>(r) * n + this->Me]));
      count += static_cast<size_t>((static_cast<long long>(in[r].size()) + chunk - 1) / chunk);
      count += static_cast<size_t>((sizes[r] + chunk - 1) / chunk);
    }
  }
  std::vector<vtkMPICommunicator::Request> requests(count);
  size_t k = 0;
  const int tag = 73901;
  for (int r = 0; r < n; ++r)
  {
    for (long long at = 0; r != this->Me && at < static_cast<long long>(in[r].size()); at += chunk)
    {
      const int length = static_cast<int>(std::min<long long>(chunk, in[r].size() - at));
      this->Mpi->NoBlockReceive(in[r].data() + at, length, r, tag, requests[k++]);
    }
  }
  for (int r = 0; r < n; ++r)
  {
    for (long long at = 0; r != this->Me && at < sizes[r]; at += chunk)
    {
      const int length = static_cast<int>(std::min<long long>(chunk, sizes[r] - at));
      this->Mpi->NoBlockSend(out[r].data() + at, length, r, tag, requests[k++]);
      this->Sent += length;
    }
  }
  if (k > 0)
  {
    this->Mpi->WaitAll(static_cast<int>(k), requests.data());
  }
  return in;
}

void MPIParts::Swap(const std::vector<int>& ranks, std::vector<std::vector<double>>& send,
  std::vector<std::vector<double>>& recv)
{
  std::vector<vtkMPICommunicator::Request> requests(2 * ranks.size());
  size_t k = 0;
  const int tag = 73902;
  for (size_t i = 0; i < ranks.size(); ++i)
  {
    if (!recv[i].empty())
    {
      this->Mpi->NoBlockReceive(
        recv[i].data(), static_cast<int>(recv[i].size()), ranks[i], tag, requests[k++]);
    }
  }
  for (size_t i = 0; i < ranks.size(); ++i)
  {
    if (!send[i].empty())
    {
      this->Mpi->NoBlockSend(
        send[i].data(), static_cast<int>(send[i].size()), ranks[i], tag, requests[k++]);
      this->Sent += static_cast<double>(send[i].size() * sizeof(double));
    }
  }
  if (k > 0)
  {
    this->Mpi->WaitAll(static_cast<int>(k), requests.data());
  }
}

std::vector<Box> MPIParts::GatherBoxes(const Box& mine)
{
  std::vector<double> gathered(static_cast<size_t>(6 * this->N));
  this->C->AllGather(mine.data(), gathered.data(), 6);
  std::vector<Box> boxes(static_cast<size_t>(this->N));
  for (int r = 0; r < this->N; ++r)
  {
    std::copy(gathered.begin() + 6 * r, gathered.begin() + 6 * r + 6, boxes[r].begin());
  }
  return boxes;
}

std::vector<std::vector<mp::Index>> MPIParts::MatchRows(size_t keyBytes,
  const std::function<std::vector<mp::Index>(int)>& asks,
  const std::function<void(mp::Index, char*)>& key,
  const std::function<mp::Index(const char*)>& find)
{
  const int n = this->N;
  // To each higher process, the keys of the rows this one may share with it.
  std::vector<std::vector<mp::Index>> asked(static_cast<size_t>(n));
  std::vector<std::vector<char>> out(static_cast<size_t>(n));
  for (int r = this->Me + 1; r < n; ++r)
  {
    asked[r] = asks(r);
    out[r].resize(asked[r].size() * keyBytes);
    for (size_t i = 0; i < asked[r].size(); ++i)
    {
      key(asked[r][i], out[r].data() + i * keyBytes);
    }
  }
  std::vector<std::vector<char>> in = this->AllToAll(out);
  // From each lower process: which of its keys this one has.
  std::vector<std::vector<mp::Index>> shared(static_cast<size_t>(n));
  std::vector<std::vector<char>> answers(static_cast<size_t>(n));
  for (int s = 0; s < this->Me; ++s)
  {
    for (size_t at = 0; at + keyBytes <= in[s].size(); at += keyBytes)
    {
      const mp::Index row = find(in[s].data() + at);
      answers[s].push_back(row >= 0);
      if (row >= 0)
      {
        shared[s].push_back(row);
      }
    }
  }
  std::vector<std::vector<char>> replies = this->AllToAll(answers);
  for (int r = this->Me + 1; r < n; ++r)
  {
    for (size_t i = 0; i < replies[r].size() && i < asked[r].size(); ++i)
    {
      if (replies[r][i])
      {
        shared[r].push_back(asked[r][i]);
      }
    }
  }
  return shared;
}
} // namespace mpvtk
