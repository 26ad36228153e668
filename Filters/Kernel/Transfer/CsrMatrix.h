// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CsrMatrix.h
 * @brief The operator's sparse matrices: compressed rows, readable as arrays.
 *
 * Rows start at RowStart[i], end at RowStart[i + 1]; their column indices
 * (32 bits: the operator refuses spaces of 2^31 or more functions, and the
 * solve streams the columns once per iteration) are sorted and unique.
 * These are the arrays a caller reads out (e.g. into scipy.sparse.csr_matrix).
 */
#ifndef MeshProjection_Kernel_CsrMatrix_h
#define MeshProjection_Kernel_CsrMatrix_h

#include "Mesh/LargeArray.h"
#include "Mesh/MeshView.h"

#include <algorithm>
#include <cstdint>

namespace mp
{
using Column = std::int32_t;

struct CsrMatrix
{
  Index Rows = 0;
  Index Columns = 0;
  LargeVector<Index> RowStart{ 0 };
  /// Written whole by their builders (mostly in concurrent tasks), not zeroed first.
  UninitializedLargeVector<Column> ColumnIndex;
  UninitializedLargeVector<double> Values;

  Index NonZeros() const { return this->RowStart.empty() ? 0 : this->RowStart.back(); }
  /// The identity of `n` rows.
  static CsrMatrix Identity(Index n)
  {
    CsrMatrix m;
    m.Rows = m.Columns = n;
    m.RowStart.resize(static_cast<size_t>(n) + 1);
    m.ColumnIndex.resize(static_cast<size_t>(n));
    m.Values.resize(static_cast<size_t>(n));
    m.RowStart[0] = 0;
    for (Index i = 0; i < n; ++i)
    {
      m.RowStart[i + 1] = i + 1;
      m.ColumnIndex[i] = static_cast<Column>(i);
      m.Values[i] = 1.0;
    }
    return m;
  }
  /// Position of entry (i, k) in Values; when absent, where it would go in the row.
  Index Find(Index i, Index k) const
  {
    const Column* begin = this->ColumnIndex.data() + this->RowStart[i];
    const Column* end = this->ColumnIndex.data() + this->RowStart[i + 1];
    return static_cast<Index>(
      std::lower_bound(begin, end, static_cast<Column>(k)) - this->ColumnIndex.data());
  }
  /**
   * Find() for `n` columns of row i at once (each in the row): on a short
   * row by counting the row's columns below each, without branches (the
   * binary searches' branches mispredict on rows of a few entries); by
   * Find() on a long one.
   */
  void FindAll(Index i, const Index* k, int n, Index* positions) const
  {
    const Index begin = this->RowStart[i];
    const Index end = this->RowStart[i + 1];
    if (end - begin > 32)
    {
      for (int j = 0; j < n; ++j)
      {
        positions[j] = this->Find(i, k[j]);
      }
      return;
    }
    const Column* columns = this->ColumnIndex.data();
    for (int j = 0; j < n; ++j)
    {
      const Column wanted = static_cast<Column>(k[j]);
      Index below = 0;
      for (Index p = begin; p < end; ++p)
      {
        below += columns[p] < wanted;
      }
      positions[j] = begin + below;
    }
  }
  /// The entry (i, k), 0 when the pattern does not hold it.
  double Entry(Index i, Index k) const
  {
    const Index p = this->Find(i, k);
    return p < this->RowStart[i + 1] && this->ColumnIndex[p] == k ? this->Values[p] : 0.0;
  }
  /**
   * Rows longer than this (a mass matrix's have a few dozen entries at
   * most; P^T M P's rows at a fringe's stencils have hundreds) are summed
   * by SumLongRow.
   */
  static constexpr Index LongRow = 48;
  /**
   * Row entries [a, b) times X (one vector): SumRow in one running sum (in
   * the order of the pair loop below), SumLongRow in four, added
   * ((s0 + s1) + (s2 + s3)) at the end: a long row's single chain of
   * dependent additions would be latency bound.
   */
  static double SumRow(
    const double* values, const Column* columns, const double* X, Index a, Index b)
  {
    double s = 0.0;
    for (Index j = a; j < b; ++j)
    {
      s += values[j] * X[columns[j]];
    }
    return s;
  }
  static double SumLongRow(
    const double* values, const Column* columns, const double* X, Index a, Index b)
  {
    double s[4] = { 0.0, 0.0, 0.0, 0.0 };
    Index j = a;
    for (; j + 3 < b; j += 4)
    {
      s[0] += values[j] * X[columns[j]];
      s[1] += values[j + 1] * X[columns[j + 1]];
      s[2] += values[j + 2] * X[columns[j + 2]];
      s[3] += values[j + 3] * X[columns[j + 3]];
    }
    for (int k = 0; j < b; ++j, ++k)
    {
      s[k] += values[j] * X[columns[j]];
    }
    return (s[0] + s[1]) + (s[2] + s[3]);
  }
  /**
   * Y = A X on rows [begin, end) for `c` vectors stored side by side (row i
   * of X holds entries i*c .. i*c + c-1): the matrix is read once for all.
   */
  template <int FixedC>
  void Multiply(const double* X, double* Y, int dynamicC, Index begin, Index end) const
  {
    const int c = FixedC > 0 ? FixedC : dynamicC;
    const Index* start = this->RowStart.data();
    const Column* columns = this->ColumnIndex.data();
    const double* values = this->Values.data();
    Index i = begin;
    if constexpr (FixedC == 1)
    {
      // Two rows at a time, each with its own running sum in its own order
      // (the same additions as one row at a time, the same values): the
      // second row's chain of dependent additions runs beside the first's
      // instead of after it (one chain was latency bound).
      for (; i + 1 < end; i += 2)
      {
        const Index a0 = start[i];
        const Index b0 = start[i + 1];
        const Index b1 = start[i + 2];
        const Index n0 = b0 - a0;
        const Index n1 = b1 - b0;
        if (n0 > LongRow || n1 > LongRow)
        {
          // (Each row by its own length's rule: its sum does not depend on
          // the row it is paired with.)
          Y[i] = n0 > LongRow ? SumLongRow(values, columns, X, a0, b0)
                              : SumRow(values, columns, X, a0, b0);
          Y[i + 1] = n1 > LongRow ? SumLongRow(values, columns, X, b0, b1)
                                  : SumRow(values, columns, X, b0, b1);
          continue;
        }
        const Index both = n0 < n1 ? n0 : n1;
        double s0 = 0.0;
        double s1 = 0.0;
        for (Index j = 0; j < both; ++j)
        {
          s0 += values[a0 + j] * X[columns[a0 + j]];
          s1 += values[b0 + j] * X[columns[b0 + j]];
        }
        for (Index j = both; j < n0; ++j)
        {
          s0 += values[a0 + j] * X[columns[a0 + j]];
        }
        for (Index j = both; j < n1; ++j)
        {
          s1 += values[b0 + j] * X[columns[b0 + j]];
        }
        Y[i] = s0;
        Y[i + 1] = s1;
      }
    }
    for (; i < end; ++i)
    {
      double* y = Y + i * c;
      if constexpr (FixedC == 1)
      {
        if (start[i + 1] - start[i] > LongRow)
        {
          y[0] = SumLongRow(values, columns, X, start[i], start[i + 1]);
          continue;
        }
      }
      if constexpr (FixedC > 0)
      {
        // The row's sums in registers, stored once (through y, which the
        // compiler must assume may alias the matrix, each term would be a
        // store and a reload); the same additions in the same order.
        double sum[FixedC] = {};
        for (Index p = start[i]; p < start[i + 1]; ++p)
        {
          const double v = values[p];
          const double* x = X + static_cast<Index>(columns[p]) * FixedC;
          for (int k = 0; k < FixedC; ++k)
          {
            sum[k] += v * x[k];
          }
        }
        for (int k = 0; k < FixedC; ++k)
        {
          y[k] = sum[k];
        }
      }
      else
      {
        std::fill(y, y + c, 0.0);
        for (Index p = start[i]; p < start[i + 1]; ++p)
        {
          const double v = values[p];
          const double* x = X + static_cast<Index>(columns[p]) * c;
          for (int k = 0; k < c; ++k)
          {
            y[k] += v * x[k];
          }
        }
      }
    }
  }
  /// Multiply with compile-time widths for the usual few fields.
  void MultiplyRows(const double* X, double* Y, int c, Index begin, Index end) const
  {
    switch (c)
    {
      case 1:
        return this->Multiply<1>(X, Y, c, begin, end);
      case 2:
        return this->Multiply<2>(X, Y, c, begin, end);
      case 3:
        return this->Multiply<3>(X, Y, c, begin, end);
      default:
        return this->Multiply<0>(X, Y, c, begin, end);
    }
  }
};
} // namespace mp

#endif
