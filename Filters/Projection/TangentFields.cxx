// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/TangentFields.h"

#include "vtkCellData.h"
#include "vtkCellTypes.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkUnsignedCharArray.h"

#include "Adapter/Ghosts.h"
#include "Adapter/SimplexMesh.h"
#include "Mesh/AlignedSum.h"
#include "Mesh/Vec3.h"
#include "Parallel/Parts.h"
#include "Projection/Messages.h"
#include "Projection/Settings.h"
#include "Projection/SourceFields.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace mpvtk
{
using mp::AddAligned;
using mp::Dot;
namespace
{
/// The area vector of a polygon (Newell), or the chord of a line, of points `ids`.
void Direction(vtkDataSet* data, vtkIdList* ids, int dimension, double* d)
{
  d[0] = d[1] = d[2] = 0.0;
  const vtkIdType n = ids->GetNumberOfIds();
  if (n < 2)
  {
    return;
  }
  double first[3], last[3];
  data->GetPoint(ids->GetId(0), first);
  data->GetPoint(ids->GetId(n - 1), last);
  if (dimension == 1)
  {
    for (int k = 0; k < 3; ++k)
    {
      d[k] = last[k] - first[k];
    }
    return;
  }
  // Newell's sum, relative to the first point (the same vector, less cancellation).
  double a[3], b[3];
  for (vtkIdType i = 0; i < n; ++i)
  {
    data->GetPoint(ids->GetId(i), a);
    data->GetPoint(ids->GetId((i + 1) % n), b);
    for (int k = 0; k < 3; ++k)
    {
      a[k] -= first[k];
      b[k] -= first[k];
    }
    d[0] += 0.5 * (a[1] * b[2] - a[2] * b[1]);
    d[1] += 0.5 * (a[2] * b[0] - a[0] * b[2]);
    d[2] += 0.5 * (a[0] * b[1] - a[1] * b[0]);
  }
}

/// A triangle strip's area vector: its triangles', each oriented as the strip's first.
void StripDirection(vtkDataSet* data, vtkIdList* ids, double* d)
{
  d[0] = d[1] = d[2] = 0.0;
  vtkNew<vtkIdList> triangle;
  triangle->SetNumberOfIds(3);
  for (vtkIdType i = 0; i + 2 < ids->GetNumberOfIds(); ++i)
  {
    const bool odd = (i % 2) != 0;
    triangle->SetId(0, ids->GetId(i));
    triangle->SetId(1, ids->GetId(odd ? i + 2 : i + 1));
    triangle->SetId(2, ids->GetId(odd ? i + 1 : i + 2));
    double t[3];
    Direction(data, triangle, 2, t);
    for (int k = 0; k < 3; ++k)
    {
      d[k] += t[k];
    }
  }
}

/// A cell's direction: its polygon's area vector or its line's chord.
void CellDirection(vtkDataSet* data, int type, vtkIdList* ids, double* d)
{
  if (type == VTK_PIXEL && ids->GetNumberOfIds() == 4)
  {
    // A pixel's points are in raster order: its boundary is 0, 1, 3, 2.
    const vtkIdType p2 = ids->GetId(2);
    ids->SetId(2, ids->GetId(3));
    ids->SetId(3, p2);
  }
  Direction(data, ids, vtkCellTypes::GetDimension(type), d);
}
} // namespace

bool IsTangentArray(const Settings& settings, vtkDataArray* array)
{
  const char* name = array->GetName();
  return name &&
    std::find(settings.TangentArrays.begin(), settings.TangentArrays.end(), name) !=
    settings.TangentArrays.end();
}

std::vector<double> CellDirections(vtkDataSet* data, int dimension)
{
  const vtkIdType n = data->GetNumberOfCells();
  std::vector<double> d(static_cast<size_t>(3 * n), 0.0);
  vtkUnsignedCharArray* ghosts = data->GetCellData()->GetGhostArray();
  vtkNew<vtkIdList> ids;
  // (Serial: GetCellPoints of some datasets is not thread-safe before their first call.)
  for (vtkIdType c = 0; c < n; ++c)
  {
    const int type = data->GetCellType(c);
    if (IsLeftOutGhost(ghosts, c) || vtkCellTypes::GetDimension(type) != dimension)
    {
      continue;
    }
    data->GetCellPoints(c, ids);
    if (type == VTK_TRIANGLE_STRIP)
    {
      StripDirection(data, ids, &d[3 * c]);
    }
    else
    {
      CellDirection(data, type, ids, &d[3 * c]);
    }
  }
  return d;
}

std::vector<double> PointDirections(vtkDataSet* data, int dimension)
{
  const vtkIdType n = data->GetNumberOfPoints();
  std::vector<double> d(static_cast<size_t>(3 * n), 0.0);
  vtkUnsignedCharArray* ghosts = data->GetCellData()->GetGhostArray();
  vtkNew<vtkIdList> ids;
  vtkNew<vtkIdList> part;
  // In the cells' order: the same sums for the same dataset.
  for (vtkIdType c = 0; c < data->GetNumberOfCells(); ++c)
  {
    const int type = data->GetCellType(c);
    if (IsLeftOutGhost(ghosts, c) || vtkCellTypes::GetDimension(type) != dimension)
    {
      continue;
    }
    data->GetCellPoints(c, ids);
    double w[3];
    if (dimension == 1)
    {
      // A polyline's segments each at their two ends (its chord says nothing of its points).
      part->SetNumberOfIds(2);
      for (vtkIdType i = 0; i + 1 < ids->GetNumberOfIds(); ++i)
      {
        part->SetId(0, ids->GetId(i));
        part->SetId(1, ids->GetId(i + 1));
        Direction(data, part, 1, w);
        AddAligned(&d[3 * part->GetId(0)], w);
        AddAligned(&d[3 * part->GetId(1)], w);
      }
      continue;
    }
    if (type == VTK_TRIANGLE_STRIP)
    {
      StripDirection(data, ids, w);
    }
    else
    {
      CellDirection(data, type, ids, w);
    }
    for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
    {
      AddAligned(&d[3 * ids->GetId(i)], w);
    }
  }
  return d;
}

double RemoveNormalPart(double* v, const double* d, int dimension)
{
  const double length2 = Dot(d, d);
  if (!(length2 > 0) || !std::isfinite(length2))
  {
    return 0.0;
  }
  const double along = Dot(v, d) / length2;
  double removed[3];
  for (int k = 0; k < 3; ++k)
  {
    // Surfaces: the part along the normal goes; curves: all but the part along the tangent.
    removed[k] = dimension == 1 ? v[k] - along * d[k] : along * d[k];
  }
  for (int k = 0; k < 3; ++k)
  {
    v[k] -= removed[k];
  }
  return std::sqrt(Dot(removed, removed));
}

namespace
{
/**
 * The directions of points at the same coordinates summed, each with all
 * of them: a Source in pieces (processes' parts gathered without global
 * ids, a composite's blocks appended) has its points on the cuts once per
 * piece, whose cells together are the point's star.
 */
void JoinCoincident(vtkDataSet* data, std::vector<double>& d)
{
  const vtkIdType n = data->GetNumberOfPoints();
  std::vector<std::array<double, 3>> x(static_cast<size_t>(n));
  for (vtkIdType p = 0; p < n; ++p)
  {
    data->GetPoint(p, x[p].data());
  }
  std::vector<vtkIdType> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
    [&](vtkIdType a, vtkIdType b) { return x[a] < x[b] || (x[a] == x[b] && a < b); });
  for (vtkIdType begin = 0, end = 0; begin < n; begin = end)
  {
    end = begin + 1;
    while (end < n && x[order[end]] == x[order[begin]])
    {
      ++end;
    }
    if (end - begin == 1)
    {
      continue;
    }
    double sum[3] = { 0.0, 0.0, 0.0 };
    for (vtkIdType i = begin; i < end; ++i)
    {
      AddAligned(sum, &d[3 * order[i]]);
    }
    for (vtkIdType i = begin; i < end; ++i)
    {
      std::copy_n(sum, 3, &d[3 * order[i]]);
    }
  }
}

/// The normal part of tangent array a of `g` removed at every function of the Source.
void RemoveFromSourceArray(const SimplexMesh& mesh, int association, int a,
  const std::vector<double>& cells, const std::vector<double>& points, GatheredFields& g,
  double& removedMost, double& fieldMost)
{
  const int width = g.Components;
  const int offset = g.Offsets[a];
  const vtkIdType functions = static_cast<vtkIdType>(g.Values.size() / std::max(width, 1));
  for (vtkIdType f = 0; f < functions; ++f)
  {
    // P1 functions are the kernel's points; P0 ones the dataset's cells.
    const vtkIdType at = association == PointArrays ? mesh.DataSetPoint(f) : f;
    const double* d = association == PointArrays ? &points[3 * at] : &cells[3 * at];
    double* v = &g.Values[f * width + offset];
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
    {
      continue; // (a NaN group's hole)
    }
    fieldMost = std::max(fieldMost, std::sqrt(Dot(v, v)));
    removedMost = std::max(removedMost, RemoveNormalPart(v, d, mesh.Dimension()));
  }
}
} // namespace

void RemoveSourceNormalParts(vtkDataSet* source, const SimplexMesh& mesh, const Settings& settings,
  Messages& messages, Parts& parts, GatheredFields fields[2])
{
  if (settings.TangentArrays.empty())
  {
    return;
  }
  const int dimension = mesh.Dimension();
  const bool applies = dimension == 1 || dimension == 2;
  std::vector<double> cells, points;
  for (int association = 0; association < 2; ++association)
  {
    GatheredFields& g = fields[association];
    const char* kind = association == PointArrays ? "point" : "cell";
    for (int a = 0; a < static_cast<int>(g.Arrays.size()); ++a)
    {
      vtkDataArray* array = g.Arrays[a];
      if (!IsTangentArray(settings, array))
      {
        continue;
      }
      const std::string label = array->GetName();
      if (array->GetNumberOfComponents() != 3)
      {
        messages.WarnOnce(std::string("tangent/components/") + kind + "/" + label,
          "TangentArrays: Source " + std::string(kind) + " array '" + label + "' has " +
            std::to_string(array->GetNumberOfComponents()) +
            " components, not 3: it is projected as an ordinary array.");
        continue;
      }
      double most[2] = { 0.0, 0.0 }; // removed, field
      // (A volume Source keeps its vectors: the normal part is removed on
      // Input alone, a surface or curve inside it. A process without Source
      // cells has nothing to remove but takes part in the maxima.)
      if (applies && cells.empty())
      {
        cells = CellDirections(source, dimension);
        points = PointDirections(source, dimension);
        JoinCoincident(source, points);
      }
      if (applies)
      {
        RemoveFromSourceArray(mesh, association, a, cells, points, g, most[0], most[1]);
      }
      parts.Maximum(most, 2);
      if (most[0] > LargeNormalPart * most[1])
      {
        messages.WarnOnce(std::string("tangent/source/") + kind + "/" + label,
          "TangentArrays: Source " + std::string(kind) + " array '" + label +
            "' is not tangent to the Source: its normal part, up to " + std::to_string(most[0]) +
            " for a largest magnitude of " + std::to_string(most[1]) +
            ", is removed before the projection.");
      }
    }
  }
}

TargetTangents::TargetTangents(
  vtkDataSet* data, const SimplexMesh& mesh, const mp::SolverHooks& pointHooks, vtkIdType pointRows)
  : Data(data)
  , Mesh(mesh)
  , Hooks(pointHooks)
  , PointRows(pointRows)
  , Dimension(mesh.Dimension())
{}

const std::vector<double>& TargetTangents::Directions(bool points)
{
  if (!points)
  {
    if (!this->HaveCells)
    {
      this->Cells = CellDirections(this->Data, this->Dimension);
      this->HaveCells = true;
    }
    return this->Cells;
  }
  if (!this->HavePoints)
  {
    this->Points = PointDirections(this->Data, this->Dimension);
    this->HavePoints = true;
    if (this->Hooks.Exchange)
    {
      this->CompleteSharedSums();
    }
  }
  return this->Points;
}

void TargetTangents::CompleteSharedSums()
{
  // In the solver's rows (the kernel's point order; rows beyond: zero).
  // Each process's sum has its own sign: the processes first agree on the
  // axis of each shared point (AlignedSum.h), whose sign each part then
  // takes before the parts are added.
  const vtkIdType n = this->Data->GetNumberOfPoints();
  const size_t rows = static_cast<size_t>(std::max(this->PointRows, n));
  std::vector<double> sums(3 * rows, 0.0);
  std::vector<double> outer(6 * rows, 0.0);
  for (vtkIdType f = 0; f < n; ++f)
  {
    std::copy_n(&this->Points[3 * this->Mesh.DataSetPoint(f)], 3, &sums[3 * f]);
    mp::AddOuter(&outer[6 * f], &sums[3 * f]);
  }
  this->Hooks.Exchange(outer.data(), 6);
  for (vtkIdType f = 0; f < n; ++f)
  {
    double axis[3];
    mp::PrincipalAxis(&outer[6 * f], axis);
    mp::AlignWithAxis(&sums[3 * f], axis);
  }
  this->Hooks.Exchange(sums.data(), 3);
  for (vtkIdType f = 0; f < n; ++f)
  {
    std::copy_n(&sums[3 * f], 3, &this->Points[3 * this->Mesh.DataSetPoint(f)]);
  }
}

std::vector<double> TargetTangents::Remove(double* values, vtkIdType functions, bool points,
  const std::vector<char>& keep, double fill, double& largestRemoved, double& largestField)
{
  const std::vector<double>& d = this->Directions(points);
  std::vector<double> removed(static_cast<size_t>(functions), fill);
  for (vtkIdType f = 0; f < functions; ++f)
  {
    double* v = values + 3 * f;
    if (!keep[f])
    {
      continue;
    }
    largestField = std::max(largestField, std::sqrt(Dot(v, v)));
    removed[f] = RemoveNormalPart(v, &d[3 * f], this->Dimension);
    largestRemoved = std::max(largestRemoved, removed[f]);
  }
  return removed;
}
} // namespace mpvtk
