// SPDX-License-Identifier: BSD-3-Clause
#include "Adapter/SourceLocator.h"

#include <algorithm>
#include <utility>

namespace mpvtk
{
SourceLocator::SourceLocator(const SimplexMesh& mesh)
  : Mesh(mesh)
{
  // A 2D mesh outside the planes z = constant spreads over 3D boxes.
  // (Curves and surfaces in space too.)
  const bool space = mesh.Dimension() == 1 ||
    (mesh.Dimension() == 2 && (!mesh.Frame().IsIdentity() || mesh.View().IsSurfaceMesh()));
  mp::MeshView view = mesh.View();
  view.Points = mesh.SpacePoints();
  view.SpaceDimension = space ? 3 : mesh.Dimension();
  this->Flat = view.SpaceDimension == 2;
  this->Bins.reset(new mp::BoxGridLocator(view));
}

SourceLocator::SourceLocator(
  const SimplexMesh& mesh, std::unique_ptr<mp::CandidateLocator> bins, bool flat)
  : Mesh(mesh)
  , Bins(std::move(bins))
  , Flat(flat)
{}

std::unique_ptr<mp::CandidateLocator> SourceLocator::NewForThread() const
{
  return std::unique_ptr<mp::CandidateLocator>(
    new SourceLocator(this->Mesh, this->Bins->NewForThread(), this->Flat));
}

SourceLocator::~SourceLocator() = default;

void SourceLocator::ToSpace(const double box[6], double bounds[6]) const
{
  // 2D: the kernel works in the frame's (x, y); the source lies in its own plane.
  std::copy(box, box + 6, bounds);
  if (this->Mesh.Dimension() == 2 && !this->Mesh.View().IsSurfaceMesh())
  {
    this->Mesh.Frame().BoxToSpace(box, bounds);
  }
  if (this->Flat)
  {
    bounds[4] = bounds[5] = 0.0; // the bins' cells have z = 0
  }
}

void SourceLocator::FindCandidates(const double box[6], std::vector<mp::Index>& cells)
{
  double bounds[6];
  this->ToSpace(box, bounds);
  this->Bins->FindCandidates(bounds, cells);
}

bool SourceLocator::Outside(const double* q)
{
  // Exact only on the coordinates the kernel's intersections read.
  return this->Flat && this->Mesh.Frame().IsIdentity() && this->Bins->Outside(q);
}

void SourceLocator::FindBoundaryCandidates(const double box[6], std::vector<mp::Index>& cells)
{
  double bounds[6];
  this->ToSpace(box, bounds);
  this->Bins->FindBoundaryCandidates(bounds, cells);
}
} // namespace mpvtk
