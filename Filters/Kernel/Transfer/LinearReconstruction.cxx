// SPDX-License-Identifier: BSD-3-Clause
// LinearReconstruction's geometry (LinearReconstruction.h): Prepare's steps
// (the parents' simplices, centroids and frames, the sites, the cells
// around them, the face neighbours) and the neighbours they give. The
// fields' reconstruction: LinearReconstructionFit.cxx.
#include "Transfer/LinearReconstruction.h"

#include "Geometry/CellGeometry.h"
#include "Mesh/CellNeighbors.h"
#include "Transfer/CsrBuilder.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mp
{
namespace
{
/// An orthonormal frame (m rows) of simplex c's plane or line, by
/// Gram-Schmidt on its edges; false when the simplex is degenerate.
bool SimplexFrame(const MeshView& mesh, Index c, double* frame)
{
  double e[3][3];
  SimplexEdges(mesh, c, e);
  for (int a = 0; a < mesh.CellDimension; ++a)
  {
    double v[3] = { e[a][0], e[a][1], e[a][2] };
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int b = 0; b < a; ++b)
    {
      const double* t = frame + 3 * b;
      const double dot = v[0] * t[0] + v[1] * t[1] + v[2] * t[2];
      for (int i = 0; i < 3; ++i)
      {
        v[i] -= dot * t[i];
      }
    }
    const double rest = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(rest > 1e-12 * length))
    {
      return false;
    }
    for (int i = 0; i < 3; ++i)
    {
      frame[3 * a + i] = v[i] / rest;
    }
  }
  return true;
}

} // namespace

void LinearReconstruction::Prepare(const MeshView& mesh, const TaskRunner& runner)
{
  this->Mesh = &mesh;
  this->GroupSimplices();
  this->MeasureParents(runner);
  // The face table by point ids (the mesh's own when it has one), then the
  // sites; where copies of points were joined, the table again on the sites.
  std::vector<NeighborId> built;
  const NeighborId* across = mesh.Neighbors;
  if (!across)
  {
    MeshView own = mesh;
    own.Around = nullptr;
    built.assign(static_cast<size_t>(mesh.NumberOfCells * mesh.CornersPerCell()), -1);
    BuildFaceNeighbors(own, built.data(), runner);
    across = built.data();
  }
  this->FindSites(across);
  if (this->JoinCopies)
  {
    this->MatchFacesOnSites(runner, built);
    across = built.data();
  }
  this->GatherAroundSites(runner);
  this->FindFaceNeighbors(across, runner);
}

void LinearReconstruction::GroupSimplices()
{
  // Slots: the parents in the order of their first simplex, so that a
  // parent's neighbours, numbered alike, lie near it in memory whatever the
  // dataset's numbering (the kernel's cells are in space order). Then a
  // counting sort of the simplices by slot.
  const MeshView& mesh = *this->Mesh;
  const Index parents = mesh.Parents();
  const Index cells = mesh.NumberOfCells;
  this->SlotOf.assign(static_cast<size_t>(parents), -1);
  this->ParentOfSlot.resize(static_cast<size_t>(parents));
  Index slots = 0;
  for (Index c = 0; c < cells; ++c)
  {
    Index& slot = this->SlotOf[mesh.ParentOf(c)];
    if (slot < 0)
    {
      slot = slots;
      this->ParentOfSlot[slots++] = mesh.ParentOf(c);
    }
  }
  for (Index p = 0; p < parents; ++p)
  {
    if (this->SlotOf[p] < 0) // (a parent without simplices: last)
    {
      this->SlotOf[p] = slots;
      this->ParentOfSlot[slots++] = p;
    }
  }
  this->SlotsAreParents = true;
  for (Index p = 0; p < parents && this->SlotsAreParents; ++p)
  {
    this->SlotsAreParents = this->SlotOf[p] == p;
  }
  GroupInRows(
    parents,
    [&](auto put) {
      for (Index c = 0; c < cells; ++c)
      {
        put(this->SlotOf[mesh.ParentOf(c)], c);
      }
    },
    this->SimplexStart, this->Simplices);
}

void LinearReconstruction::MeasureParents(const TaskRunner& runner)
{
  const MeshView& mesh = *this->Mesh;
  const Index parents = mesh.Parents();
  const bool framed = !mesh.IsVolumeMesh();
  this->Centroids.assign(3 * static_cast<size_t>(parents), 0.0);
  this->Flat.assign(static_cast<size_t>(parents), 0);
  this->Frames.assign(framed ? 3 * static_cast<size_t>(mesh.CellDimension) * parents : 0, 0.0);
  runner.ForRanges(
    parents,
    [&](Index begin, Index end) {
      for (Index p = begin; p < end; ++p)
      {
        const Index* simplices = this->Simplices.data() + this->SimplexStart[p];
        const Index count = this->SimplexStart[p + 1] - this->SimplexStart[p];
        // (A parent of no measure is no part of any integral: a neighbour of
        // none; its centroid serves its own, unread, gradient.)
        this->Flat[p] = !(CellCentroid(mesh, simplices, count, &this->Centroids[3 * p]) > 0.0);
        // The frame of its first simplex that has one.
        bool hasFrame = !framed;
        for (Index i = 0; i < count && !hasFrame; ++i)
        {
          hasFrame = SimplexFrame(
            mesh, simplices[i], &this->Frames[3 * mesh.CellDimension * static_cast<size_t>(p)]);
        }
      }
      return 0;
    },
    1024);
}

void LinearReconstruction::FindSites(const NeighborId* across)
{
  // Copies of a point can only be where faces have no neighbour by ids (two
  // cells that share a point by coordinates but not by id are not matched
  // there): the points of those faces, in the order of their coordinates,
  // equal ones side by side. Each point is its own site, a copy its run's
  // first point's.
  const MeshView& mesh = *this->Mesh;
  const Index points = mesh.AllPoints(); // sites are places: geometric points too
  const int space = mesh.SpaceDimension;
  const int corners = mesh.CornersPerCell();
  this->Site.resize(static_cast<size_t>(points));
  for (Index q = 0; q < points; ++q)
  {
    this->Site[q] = q;
  }
  this->Sites = points;
  this->JoinCopies = false;
  std::vector<Index> open;
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    for (int k = 0; k < corners; ++k)
    {
      if (across[c * corners + k] < 0)
      {
        for (int m = 1; m < corners; ++m)
        {
          open.push_back(mesh.Cell(c)[(k + m) % corners]);
        }
      }
    }
  }
  std::sort(open.begin(), open.end());
  open.erase(std::unique(open.begin(), open.end()), open.end());
  auto same = [&](Index a, Index b) {
    return std::equal(mesh.Point(a), mesh.Point(a) + space, mesh.Point(b));
  };
  std::sort(open.begin(), open.end(), [&](Index a, Index b) {
    return std::lexicographical_compare(
      mesh.Point(a), mesh.Point(a) + space, mesh.Point(b), mesh.Point(b) + space);
  });
  for (size_t i = 1; i < open.size(); ++i)
  {
    if (same(open[i - 1], open[i]))
    {
      this->Site[open[i]] = this->Site[open[i - 1]];
      this->JoinCopies = true;
    }
  }
}

void LinearReconstruction::MatchFacesOnSites(
  const TaskRunner& runner, std::vector<NeighborId>& across) const
{
  const MeshView& mesh = *this->Mesh;
  const Index entries = mesh.NumberOfCells * mesh.CornersPerCell();
  std::vector<Index> sites(static_cast<size_t>(entries));
  runner.ForRanges(entries, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i)
    {
      sites[i] = this->Site[mesh.Corner(i)];
    }
    return 0;
  });
  MeshView onSites = mesh;
  onSites.Connectivity = sites.data();
  onSites.Connectivity32 = nullptr;
  onSites.Neighbors = nullptr;
  onSites.Around = nullptr;
  across.assign(static_cast<size_t>(entries), -1);
  BuildFaceNeighbors(onSites, across.data(), runner);
}

void LinearReconstruction::GatherAroundSites(const TaskRunner& runner)
{
  // The parents around each site, sorted (a split parent as often as its
  // simplices there).
  const MeshView& mesh = *this->Mesh;
  const Index entries = mesh.NumberOfCells * mesh.CornersPerCell();
  GroupInRows(
    this->Sites,
    [&](auto put) {
      for (Index i = 0; i < entries; ++i)
      {
        put(this->Site[mesh.Corner(i)], this->SlotOf[mesh.ParentOf(i / mesh.CornersPerCell())]);
      }
    },
    this->AroundStart, this->Around);
  runner.ForRanges(this->Sites, [&](Index begin, Index end) {
    for (Index q = begin; q < end; ++q)
    {
      std::sort(this->Around.begin() + this->AroundStart[q],
        this->Around.begin() + this->AroundStart[q + 1]);
    }
    return 0;
  });
}

void LinearReconstruction::FindFaceNeighbors(const NeighborId* across, const TaskRunner& runner)
{
  // Per parent, the parents across its simplices' faces (`across`: the
  // simplices' face neighbours on the sites).
  const MeshView& mesh = *this->Mesh;
  const Index parents = mesh.Parents();
  const int corners = mesh.CornersPerCell();
  const int tasks = runner.TasksFor(parents, 1024);
  std::vector<std::vector<Index>> found(static_cast<size_t>(tasks));
  std::vector<Index> count(static_cast<size_t>(parents) + 1, 0);
  runner.RunAll(tasks, [&](int k) {
    for (Index p = RangeBegin(parents, k, tasks); p < RangeBegin(parents, k + 1, tasks); ++p)
    {
      const size_t first = found[k].size();
      for (Index i = this->SimplexStart[p]; i < this->SimplexStart[p + 1]; ++i)
      {
        for (int face = 0; face < corners; ++face)
        {
          const NeighborId n = across[static_cast<size_t>(this->Simplices[i] * corners + face)];
          const Index q = n >= 0 ? this->SlotOf[mesh.ParentOf(n)] : p;
          if (q != p)
          {
            found[k].push_back(q);
          }
        }
      }
      std::sort(found[k].begin() + first, found[k].end());
      found[k].erase(std::unique(found[k].begin() + first, found[k].end()), found[k].end());
      count[p + 1] = static_cast<Index>(found[k].size() - first);
    }
  });
  CountsToStarts(count); // (the tasks' lists, one after the other, are the rows)
  this->FaceStart.swap(count);
  this->Faces.clear();
  this->Faces.reserve(static_cast<size_t>(this->FaceStart.back()));
  for (const std::vector<Index>& part : found)
  {
    this->Faces.insert(this->Faces.end(), part.begin(), part.end());
  }
}

void LinearReconstruction::NeighborsOf(Index p, std::vector<Index>& neighbors) const
{
  this->SlotNeighbors(this->SlotOf[p], neighbors);
  for (Index& q : neighbors)
  {
    q = this->ParentOfSlot[q];
  }
  std::sort(neighbors.begin(), neighbors.end());
}

void LinearReconstruction::SlotNeighbors(Index p, std::vector<Index>& neighbors) const
{
  const MeshView& mesh = *this->Mesh;
  neighbors.clear();
  for (Index i = this->SimplexStart[p]; i < this->SimplexStart[p + 1]; ++i)
  {
    const CellCorners ids = mesh.Cell(this->Simplices[i]);
    for (int k = 0; k < mesh.CornersPerCell(); ++k)
    {
      const Index q = this->Site[ids[k]];
      for (Index j = this->AroundStart[q]; j < this->AroundStart[q + 1]; ++j)
      {
        if (this->Around[j] != p)
        {
          neighbors.push_back(this->Around[j]);
        }
      }
    }
  }
  std::sort(neighbors.begin(), neighbors.end());
  neighbors.erase(std::unique(neighbors.begin(), neighbors.end()), neighbors.end());
}

std::size_t LinearReconstruction::MemoryBytes() const
{
  return (this->Centroids.capacity() + this->Frames.capacity()) * sizeof(double) +
    (this->SimplexStart.capacity() + this->Simplices.capacity() + this->SlotOf.capacity() +
      this->ParentOfSlot.capacity() + this->AroundStart.capacity() + this->Around.capacity() +
      this->Site.capacity() + this->FaceStart.capacity() + this->Faces.capacity()) *
    sizeof(Index) +
    this->Flat.capacity();
}
} // namespace mp
