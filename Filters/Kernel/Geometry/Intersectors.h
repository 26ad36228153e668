// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Intersectors.h
 * @brief Which intersector a mesh's cells take: the one place that decides.
 */
#ifndef MeshProjection_Kernel_Intersectors_h
#define MeshProjection_Kernel_Intersectors_h

#include "Geometry/SegmentIntersector.h"
#include "Geometry/SurfaceIntersector.h"
#include "Geometry/TetrahedronIntersector.h"
#include "Geometry/TriangleIntersector.h"
#include "Mesh/MeshView.h"

namespace mp
{
/**
 * Calls f(static_cast<Intersector*>(nullptr)) with the intersector of
 * `mesh`'s kind (the pointer's type is the argument): segments of curves,
 * triangles of surfaces in 3D, triangles in the plane, tetrahedra.
 */
template <class F>
void WithIntersectorOf(const MeshView& mesh, F f)
{
  if (mesh.IsCurveMesh())
  {
    f(static_cast<SegmentIntersector*>(nullptr));
  }
  else if (mesh.IsSurfaceMesh())
  {
    f(static_cast<SurfaceIntersector*>(nullptr));
  }
  else if (mesh.CellDimension == 2)
  {
    f(static_cast<TriangleIntersector*>(nullptr));
  }
  else
  {
    f(static_cast<TetrahedronIntersector*>(nullptr));
  }
}
} // namespace mp

#endif
