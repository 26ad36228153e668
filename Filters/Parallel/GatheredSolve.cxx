// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file GatheredSolve.cxx
 * @brief MPIParts::SolveGathered: the solver's Direct hook on several
 *        processes, the whole system gathered and solved on process 0.
 *
 * Used only when the distributed iterations did not converge for some
 * fields, so it favours being simple and exact over scaling: every row
 * and entry travels to one process.
 */
#include "Parallel/MPIParts.h"

#include "Transfer/BlockCG.h"

#include <algorithm>
#include <unordered_map>

namespace mpvtk
{
bool MPIParts::SolveGathered(const RowSharing& shared, const mp::CsrMatrix& A, const double* B,
  double* X, int c, const std::vector<char>& converged)
{
  // The rare case of iterations that did not converge (targets covered
  // only in slivers): the whole matrix on process 0. Each process sends,
  // per row, its global id, whether it counts it and its right-hand sides
  // (complete already), then its entries by global ids (a shared row's
  // parts are summed there, as the iterations' products sum them);
  // process 0 factors the matrix and sends each process its rows' values.
  std::vector<int> open;
  for (int k = 0; k < c; ++k)
  {
    if (!converged[static_cast<size_t>(k)])
    {
      open.push_back(k);
    }
  }
  const mp::Index rows = A.Rows;
  const size_t width = open.size();
  const size_t perRow = 2 + width;
  std::vector<double> mine;
  mine.reserve(2 + static_cast<size_t>(rows) * perRow + 3 * A.Values.size());
  mine.push_back(static_cast<double>(rows));
  for (mp::Index f = 0; f < rows; ++f)
  {
    mine.push_back(static_cast<double>(shared.RowGlobal[f]));
    mine.push_back(shared.Counted[f] ? 1.0 : 0.0);
    for (int k : open)
    {
      mine.push_back(B[f * c + k]);
    }
  }
  mine.push_back(static_cast<double>(A.RowStart[rows]));
  for (mp::Index f = 0; f < rows; ++f)
  {
    for (mp::Index e = A.RowStart[f]; e < A.RowStart[f + 1]; ++e)
    {
      mine.push_back(static_cast<double>(shared.RowGlobal[f]));
      mine.push_back(static_cast<double>(shared.RowGlobal[static_cast<size_t>(A.ColumnIndex[e])]));
      mine.push_back(A.Values[e]);
    }
  }
  std::vector<std::vector<char>> out(static_cast<size_t>(this->N));
  Append(out[0], mine.data(), mine.size());
  std::vector<double>().swap(mine);
  std::vector<std::vector<char>> in = this->AllToAll(out);
  std::vector<std::vector<char>> back(static_cast<size_t>(this->N));
  if (this->Me == 0)
  {
    std::unordered_map<long long, mp::Index> index;
    auto id = [&index](double g) {
      return index.emplace(static_cast<long long>(g), static_cast<mp::Index>(index.size()))
        .first->second;
    };
    std::vector<std::vector<double>> parts(static_cast<size_t>(this->N));
    std::vector<mp::Index> row, column;
    std::vector<double> value, b;
    for (int r = 0; r < this->N; ++r)
    {
      parts[r] = Read<double>(in[r]);
      std::vector<char>().swap(in[r]);
      const std::vector<double>& v = parts[r];
      const size_t n = v.empty() ? 0 : static_cast<size_t>(v[0]);
      for (size_t i = 0; i < n; ++i)
      {
        const double* at = v.data() + 1 + i * perRow;
        const size_t g = static_cast<size_t>(id(at[0]));
        b.resize(std::max(b.size(), (g + 1) * width), 0.0);
        for (size_t k = 0; k < width && at[1] != 0.0; ++k)
        {
          b[g * width + k] = at[2 + k];
        }
      }
      const size_t first = 1 + n * perRow;
      const size_t entries = v.empty() ? 0 : static_cast<size_t>(v[first]);
      for (size_t e = 0; e < entries; ++e)
      {
        const double* at = v.data() + first + 1 + 3 * e;
        row.push_back(id(at[0]));
        column.push_back(id(at[1]));
        value.push_back(at[2]);
      }
    }
    const mp::Index total = static_cast<mp::Index>(index.size());
    b.resize(static_cast<size_t>(total) * width, 0.0);
    std::vector<double> x(b.size(), 0.0);
    const bool solved = mp::BlockCG::SolveEntries(
      total, row, column, value, b.data(), x.data(), static_cast<int>(width));
    for (int r = 0; r < this->N; ++r)
    {
      const std::vector<double>& v = parts[r];
      const size_t n = v.empty() ? 0 : static_cast<size_t>(v[0]);
      std::vector<double> answer(1, solved ? 1.0 : 0.0);
      for (size_t i = 0; i < n && solved; ++i)
      {
        const size_t g = static_cast<size_t>(index[static_cast<long long>(v[1 + i * perRow])]);
        answer.insert(answer.end(), x.begin() + g * width, x.begin() + (g + 1) * width);
      }
      Append(back[r], answer.data(), answer.size());
    }
  }
  std::vector<std::vector<char>> answers = this->AllToAll(back);
  const std::vector<double> mineBack = Read<double>(answers[0]);
  if (mineBack.empty() || mineBack[0] == 0.0)
  {
    return false;
  }
  for (mp::Index f = 0; f < rows; ++f)
  {
    for (size_t k = 0; k < width; ++k)
    {
      X[f * c + open[k]] = mineBack[1 + static_cast<size_t>(f) * width + k];
    }
  }
  return true;
}
} // namespace mpvtk
