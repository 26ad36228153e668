// SPDX-License-Identifier: BSD-3-Clause
#include "Mesh/PlaneFrame.h"

#include "Mesh/Vec3.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mp
{
namespace
{
/// The corners' box and the sum of their coordinates (for the mean).
struct CornerBox
{
  double Lo[3];
  double Hi[3];
  double Sum[3] = { 0, 0, 0 };
};

/**
 * The box and the sum of the `uses` corners of `mesh`, in one pass: per
 * block of corners its box and sum (in tasks), then the blocks' in block
 * order (the same sum for any number of tasks).
 */
void ReadCorners(const MeshView& mesh, Index uses, const TaskRunner& runner, CornerBox& box)
{
  for (int d = 0; d < 3; ++d)
  {
    box.Lo[d] = std::numeric_limits<double>::infinity();
    box.Hi[d] = -box.Lo[d];
  }
  constexpr Index Block = Index(1) << 15;
  const Index blocks = (uses + Block - 1) / Block;
  std::vector<double> partial(static_cast<size_t>(9 * blocks));
  runner.ForRanges(
    blocks,
    [&](Index first, Index last) {
      for (Index b = first; b < last; ++b)
      {
        // (In locals, kept in registers and written out once: a store
        // through `partial` at each corner was memory traffic per corner.)
        double low[3];
        double high[3];
        double sum[3] = { 0, 0, 0 };
        for (int d = 0; d < 3; ++d)
        {
          low[d] = std::numeric_limits<double>::infinity();
          high[d] = -low[d];
        }
        const Index end = std::min(uses, (b + 1) * Block);
        for (Index i = b * Block; i < end; ++i)
        {
          const double* x = mesh.Point(mesh.Corner(i));
          for (int d = 0; d < 3; ++d)
          {
            low[d] = std::min(low[d], x[d]);
            high[d] = std::max(high[d], x[d]);
            sum[d] += x[d];
          }
        }
        double* part = &partial[static_cast<size_t>(9 * b)];
        std::copy(low, low + 3, part);
        std::copy(high, high + 3, part + 3);
        std::copy(sum, sum + 3, part + 6);
      }
      return 0;
    },
    4);
  for (Index b = 0; b < blocks; ++b)
  {
    const double* part = &partial[static_cast<size_t>(9 * b)];
    for (int d = 0; d < 3; ++d)
    {
      box.Lo[d] = std::min(box.Lo[d], part[d]);
      box.Hi[d] = std::max(box.Hi[d], part[3 + d]);
      box.Sum[d] += part[6 + d];
    }
  }
}

/// Whether some cell of a mesh lying in a plane z = constant has area.
bool SomeCellHasArea(const MeshView& mesh)
{
  const int corners = mesh.CornersPerCell();
  bool area = false;
  for (Index c = 0; c < mesh.NumberOfCells && !area; ++c)
  {
    const CellCorners ids = mesh.Cell(c);
    const double* a = mesh.Point(ids[0]);
    const double* b = mesh.Point(ids[1]);
    const double* p = mesh.Point(ids[corners > 2 ? 2 : 1]);
    area = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) != 0.0;
  }
  return area;
}

/// The normal: the cells' normals summed, each turned to agree with the
/// largest one (a mesh's triangles may come in either orientation); left
/// as it is when they sum to zero.
void SummedNormal(const MeshView& mesh, double normal[3])
{
  const int corners = mesh.CornersPerCell();
  double reference[3] = { 0, 0, 0 };
  double largest = 0.0;
  std::vector<double> normals(static_cast<size_t>(3 * mesh.NumberOfCells));
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const CellCorners ids = mesh.Cell(c);
    const double* a = mesh.Point(ids[0]);
    const double* b = mesh.Point(ids[1]);
    const double* p = mesh.Point(ids[corners > 2 ? 2 : 1]);
    Vec u;
    Vec v;
    Sub(b, a, u);
    Sub(p, a, v);
    double* n = &normals[3 * c];
    Cross(u, v, n);
    const double length = Dot(n, n);
    if (length > largest)
    {
      largest = length;
      std::copy(n, n + 3, reference);
    }
  }
  double sum[3] = { 0, 0, 0 };
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const double* n = &normals[3 * c];
    const double sign = Dot(n, reference) < 0.0 ? -1.0 : 1.0;
    for (int d = 0; d < 3; ++d)
    {
      sum[d] += sign * n[d];
    }
  }
  const double length = std::sqrt(Dot(sum, sum));
  if (length > 0.0)
  {
    for (int d = 0; d < 3; ++d)
    {
      normal[d] = sum[d] / length;
    }
  }
}

/// One sign for every mesh of the plane: its largest component positive
/// (else two meshes wound the other way would get mirrored offsets).
/// Returns that component's axis.
int TurnToDominantAxis(double normal[3])
{
  int axis = 0;
  for (int d = 1; d < 3; ++d)
  {
    axis = std::fabs(normal[d]) > std::fabs(normal[axis]) ? d : axis;
  }
  if (normal[axis] < 0.0)
  {
    for (int d = 0; d < 3; ++d)
    {
      normal[d] = -normal[d];
    }
  }
  return axis;
}

/// The largest distance of the `uses` corners of `mesh` from `frame`'s plane.
double LargestDistance(const MeshView& mesh, Index uses, const PlaneFrame& frame)
{
  double largest = 0.0;
  for (Index i = 0; i < uses; ++i)
  {
    largest = std::max(largest, std::fabs(frame.Distance(mesh.Point(mesh.Corner(i)))));
  }
  return largest;
}
} // namespace

bool PlaneFrame::Fit(
  const MeshView& mesh, double& deviation, double& size, const TaskRunner& runner)
{
  *this = PlaneFrame();
  deviation = 0.0;
  size = 0.0;
  const Index uses = mesh.NumberOfCells * mesh.CornersPerCell();
  if (uses == 0)
  {
    return true;
  }
  CornerBox box;
  ReadCorners(mesh, uses, runner, box);
  const double* lo = box.Lo;
  const double* hi = box.Hi;
  for (int d = 0; d < 3; ++d)
  {
    size = std::max(size, hi[d] - lo[d]);
  }
  // Every corner at one finite z, and a cell of positive area: the plane
  // z = constant is the one the general fit below finds (every normal along
  // z; the aligned frame, at distance 0 from every corner), without its
  // four passes and the normals' array. The common 2D mesh.
  if (lo[2] == hi[2] && std::isfinite(lo[2]) && SomeCellHasArea(mesh))
  {
    std::fill(this->Normal, this->Normal + 3, 0.0);
    this->Normal[2] = 1.0;
    for (int d = 0; d < 3; ++d)
    {
      this->Origin[d] = box.Sum[d] / static_cast<double>(uses);
    }
    this->Origin[2] = 0.5 * (lo[2] + hi[2]);
    this->SetAxes();
    this->PlaneOffset = this->Origin[2];
    this->PlaneTolerance = 1e-9 * std::max(size, std::fabs(this->PlaneOffset));
    return true;
  }
  SummedNormal(mesh, this->Normal);
  const int axis = TurnToDominantAxis(this->Normal);
  // The plane through the mean of the corners.
  for (int d = 0; d < 3; ++d)
  {
    this->Origin[d] = box.Sum[d] / static_cast<double>(uses);
  }
  // The axis plane through the middle of the box along the dominant axis,
  // when the points lie in it within the tolerance (exact 2D coordinates);
  // else the fitted plane.
  PlaneFrame aligned = *this;
  std::fill(aligned.Normal, aligned.Normal + 3, 0.0);
  aligned.Normal[axis] = 1.0;
  aligned.Origin[axis] = 0.5 * (lo[axis] + hi[axis]);
  aligned.SetAxes();
  aligned.PlaneOffset = aligned.Origin[axis];
  const double alignedDeviation = LargestDistance(mesh, uses, aligned);
  aligned.PlaneTolerance = 1e-9 * std::max(size, std::fabs(aligned.PlaneOffset));
  if (alignedDeviation <= aligned.PlaneTolerance)
  {
    *this = aligned;
    deviation = alignedDeviation;
    return true;
  }
  this->SetAxes();
  this->PlaneOffset = Dot(this->Origin, this->Normal);
  deviation = LargestDistance(mesh, uses, *this);
  this->PlaneTolerance = 1e-9 * std::max(size, std::fabs(this->PlaneOffset));
  return deviation <= this->PlaneTolerance;
}

void PlaneFrame::SetAxes()
{
  const double* n = this->Normal;
  this->Axes[0] = this->Axes[1] = -1;
  // Axis planes pick coordinates, keeping a right-handed (u, v, n).
  if (n[2] == 1.0 || n[2] == -1.0)
  {
    this->Axes[0] = 0, this->Axes[1] = 1;
  }
  else if (n[0] == 1.0 || n[0] == -1.0)
  {
    this->Axes[0] = 1, this->Axes[1] = 2;
  }
  else if (n[1] == 1.0 || n[1] == -1.0)
  {
    this->Axes[0] = 2, this->Axes[1] = 0;
  }
  if (this->Axes[0] >= 0)
  {
    std::fill(this->U, this->U + 3, 0.0);
    std::fill(this->V, this->V + 3, 0.0);
    this->U[this->Axes[0]] = 1.0;
    this->V[this->Axes[1]] = 1.0;
    return;
  }
  // U along the axis least aligned with the normal, made orthogonal to it.
  int least = 0;
  for (int d = 1; d < 3; ++d)
  {
    if (std::fabs(n[d]) < std::fabs(n[least]))
    {
      least = d;
    }
  }
  double e[3] = { 0, 0, 0 };
  e[least] = 1.0;
  const double along = Dot(e, n);
  for (int d = 0; d < 3; ++d)
  {
    this->U[d] = e[d] - along * n[d];
  }
  const double length = std::sqrt(Dot(this->U, this->U));
  for (double& u : this->U)
  {
    u /= length;
  }
  this->V[0] = n[1] * this->U[2] - n[2] * this->U[1];
  this->V[1] = n[2] * this->U[0] - n[0] * this->U[2];
  this->V[2] = n[0] * this->U[1] - n[1] * this->U[0];
}

double PlaneFrame::Distance(const double* x) const
{
  return Dot(x, this->Normal) - this->PlaneOffset;
}

bool PlaneFrame::IsParallel(const PlaneFrame& other) const
{
  return AreParallel(this->Normal, other.Normal);
}

bool PlaneFrame::AreParallel(const double* a, const double* b)
{
  const double c[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
    a[0] * b[1] - a[1] * b[0] };
  return Dot(c, c) <= 1e-18;
}

void PlaneFrame::ToPlane(const double* x, double* uv) const
{
  if (this->Axes[0] >= 0)
  {
    uv[0] = x[this->Axes[0]];
    uv[1] = x[this->Axes[1]];
  }
  else
  {
    const double d[3] = { x[0] - this->Origin[0], x[1] - this->Origin[1], x[2] - this->Origin[2] };
    uv[0] = Dot(d, this->U);
    uv[1] = Dot(d, this->V);
  }
  uv[2] = 0.0;
}

void PlaneFrame::ToSpace(const double* uv, double* x) const
{
  if (this->Axes[0] >= 0)
  {
    for (int d = 0; d < 3; ++d)
    {
      x[d] = this->Normal[d] * this->PlaneOffset;
    }
    x[this->Axes[0]] = uv[0];
    x[this->Axes[1]] = uv[1];
    return;
  }
  for (int d = 0; d < 3; ++d)
  {
    x[d] = this->Origin[d] + uv[0] * this->U[d] + uv[1] * this->V[d];
  }
}

PlaneFrame PlaneFrame::Shifted(double offset) const
{
  PlaneFrame shifted = *this;
  for (int d = 0; d < 3; ++d)
  {
    shifted.Origin[d] += (offset - this->PlaneOffset) * this->Normal[d];
  }
  shifted.PlaneOffset = offset;
  return shifted;
}

void PlaneFrame::ToPlane(const MeshView& mesh, std::vector<double>& uv) const
{
  uv.resize(static_cast<size_t>(3 * mesh.AllPoints()));
  for (Index p = 0; p < mesh.AllPoints(); ++p)
  {
    this->ToPlane(mesh.Point(p), &uv[3 * p]);
  }
}

void PlaneFrame::BoxToSpace(const double box[6], double spaceBox[6]) const
{
  for (int d = 0; d < 3; ++d)
  {
    spaceBox[2 * d] = std::numeric_limits<double>::infinity();
    spaceBox[2 * d + 1] = -std::numeric_limits<double>::infinity();
  }
  for (int corner = 0; corner < 4; ++corner)
  {
    const double uv[3] = { box[corner & 1], box[2 + (corner >> 1)], 0.0 };
    double x[3];
    this->ToSpace(uv, x);
    for (int d = 0; d < 3; ++d)
    {
      spaceBox[2 * d] = std::min(spaceBox[2 * d], x[d]);
      spaceBox[2 * d + 1] = std::max(spaceBox[2 * d + 1], x[d]);
    }
  }
}
} // namespace mp
