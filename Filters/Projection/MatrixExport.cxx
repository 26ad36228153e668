// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/MatrixExport.h"

#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"

#include "Projection/OperatorCache.h"

#include <algorithm>
#include <fstream>
#include <utility>
#include <vector>

namespace mpvtk
{
namespace
{
/**
 * P's rows of this process's functions, their columns ascending (with a
 * halo P holds the ghost points' rows too, and its columns in the
 * stencils' order).
 */
mp::CsrMatrix OwnRows(const mp::CsrMatrix& P, mp::Index n)
{
  mp::CsrMatrix m;
  m.Rows = m.Columns = n;
  m.RowStart.assign(static_cast<size_t>(n) + 1, 0);
  for (mp::Index i = 0; i < n; ++i)
  {
    m.RowStart[i + 1] = m.RowStart[i] + (P.RowStart[i + 1] - P.RowStart[i]);
  }
  m.ColumnIndex.resize(static_cast<size_t>(m.NonZeros()));
  m.Values.resize(static_cast<size_t>(m.NonZeros()));
  std::vector<std::pair<mp::Column, double>> row;
  for (mp::Index i = 0; i < n; ++i)
  {
    row.clear();
    for (mp::Index q = P.RowStart[i]; q < P.RowStart[i + 1]; ++q)
    {
      row.emplace_back(P.ColumnIndex[q], P.Values[q]);
    }
    std::sort(row.begin(), row.end());
    mp::Index at = m.RowStart[i];
    for (const auto& entry : row)
    {
      m.ColumnIndex[at] = entry.first;
      m.Values[at++] = entry.second;
    }
  }
  return m;
}
} // namespace

bool FringeReachesHalo(const mp::MortarOperator& op)
{
  const mp::CsrMatrix& P = op.GetFringe().P;
  const mp::Index n = op.GetNumberOfTargetFunctions();
  for (mp::Index i = 0; P.Rows > n && i < n; ++i)
  {
    for (mp::Index q = P.RowStart[i]; q < P.RowStart[i + 1]; ++q)
    {
      if (P.ColumnIndex[q] >= n)
      {
        return true;
      }
    }
  }
  return false;
}

vtkIdType ExportMatrix(const KeptLeaf& leaf, Transfer transfer, Exported matrix,
  vtkIdTypeArray* rowStart, vtkIdTypeArray* columns, vtkDoubleArray* values)
{
  const KeptOperator& kept = leaf.Operators[transfer];
  const mp::MortarOperator& op = *kept.Operator;
  const bool mixed = matrix == Exported::MixedMass;
  mp::CsrMatrix made;
  if (matrix == Exported::FringeExtension && op.GetFringe().P.Rows == 0)
  {
    // (A P1 operator without an aggregated fringe, or a P0 one: P = I.)
    made = mp::CsrMatrix::Identity(op.GetNumberOfTargetFunctions());
  }
  else if (matrix == Exported::FringeExtension &&
    op.GetFringe().P.Rows > op.GetNumberOfTargetFunctions())
  {
    made =
      OwnRows(op.GetFringe().P, op.GetNumberOfTargetFunctions()); // (FringeReachesHalo is false)
  }
  else if (matrix == Exported::Extrapolation)
  {
    // Without an extension (the last execution did not extrapolate): the
    // identity on the valid functions of the operator's last solve.
    const bool extended = kept.ExtensionKey != 0;
    made = mp::ComposedExtension(extended ? kept.Extension : mp::Extension(),
      extended ? kept.Extension.Valid : (kept.System.Valid ? *kept.System.Valid : op.GetValid()));
  }
  const mp::CsrMatrix& m = made.Rows      ? made
    : mixed                               ? op.GetMixedMass()
    : matrix == Exported::FringeExtension ? op.GetFringe().P
                                          : op.GetTargetMass();
  // P0 rows and columns are numbered as the datasets' cells, P1 ones as
  // their points (the kernel's points of a renumbered mesh mapped back).
  const std::vector<mp::Index>* rowOrder =
    TargetSpaceOf(transfer) == mp::SpaceType::P1 && !leaf.TargetPoints.empty() ? &leaf.TargetPoints
                                                                               : nullptr;
  const mp::SpaceType columnSpace = mixed ? op.GetSourceSpace() : TargetSpaceOf(transfer);
  const std::vector<mp::Index>& columnPoints = mixed ? leaf.SourcePoints : leaf.TargetPoints;
  const std::vector<mp::Index>* columnOrder =
    columnSpace == mp::SpaceType::P1 && !columnPoints.empty() ? &columnPoints : nullptr;
  rowStart->SetNumberOfComponents(1);
  rowStart->SetNumberOfTuples(m.Rows + 1);
  columns->SetNumberOfComponents(1);
  columns->SetNumberOfTuples(m.NonZeros());
  values->SetNumberOfComponents(1);
  values->SetNumberOfTuples(m.NonZeros());
  // Kernel row of each output row.
  std::vector<mp::Index> kernelRow(static_cast<size_t>(m.Rows));
  for (mp::Index i = 0; i < m.Rows; ++i)
  {
    kernelRow[static_cast<size_t>(rowOrder ? (*rowOrder)[i] : i)] = i;
  }
  vtkIdType next = 0;
  std::vector<std::pair<mp::Index, double>> row;
  for (mp::Index r = 0; r < m.Rows; ++r)
  {
    rowStart->SetValue(r, next);
    const mp::Index i = kernelRow[r];
    row.clear();
    for (mp::Index p = m.RowStart[i]; p < m.RowStart[i + 1]; ++p)
    {
      const mp::Index j = m.ColumnIndex[p];
      row.emplace_back(columnOrder ? (*columnOrder)[j] : j, m.Values[p]);
    }
    if (columnOrder)
    {
      std::sort(row.begin(), row.end());
    }
    for (const auto& entry : row)
    {
      columns->SetValue(next, entry.first);
      values->SetValue(next++, entry.second);
    }
  }
  rowStart->SetValue(m.Rows, next);
  return m.Columns;
}

std::string WriteMatrixMarketFile(const std::string& fileName, const std::string& title,
  vtkIdType columnCount, vtkIdTypeArray* rowStart, vtkIdTypeArray* columns, vtkDoubleArray* values)
{
  std::ofstream file(fileName);
  if (!file)
  {
    return "Cannot write '" + fileName + "'.";
  }
  const vtkIdType rows = rowStart->GetNumberOfTuples() - 1;
  file << "%%MatrixMarket matrix coordinate real general\n"
       << "% MeshProjection: " << title << "\n"
       << rows << " " << columnCount << " " << values->GetNumberOfTuples() << "\n";
  file.precision(17);
  for (vtkIdType i = 0; i < rows; ++i)
  {
    for (vtkIdType p = rowStart->GetValue(i); p < rowStart->GetValue(i + 1); ++p)
    {
      file << i + 1 << " " << columns->GetValue(p) + 1 << " " << values->GetValue(p) << "\n";
    }
  }
  file.close();
  if (!file)
  {
    return "Writing '" + fileName + "' failed.";
  }
  return std::string();
}
} // namespace mpvtk
