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
#include "Geometry/TraceIntersector.h"
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

/// Whether a target of `target`'s kind lies in a volume mesh like `source`
/// (a surface in tetrahedra, a curve in triangles or tetrahedra): a trace.
inline bool IsTracePair(const MeshView& target, const MeshView& source)
{
  return source.IsVolumeMesh() && target.CellDimension < source.CellDimension &&
    ((target.IsSurfaceMesh() && source.CellDimension == 3) ||
      (target.IsCurveMesh() && target.SpaceDimension == source.SpaceDimension));
}

/**
 * The same for a pair: the traces' intersectors when `target` lies in the
 * volume mesh `source` (IsTracePair), else `target`'s own.
 */
template <class F>
void WithIntersectorOf(const MeshView& target, const MeshView& source, F f)
{
  if (!IsTracePair(target, source))
  {
    WithIntersectorOf(target, f);
  }
  else if (target.IsSurfaceMesh())
  {
    f(static_cast<SurfaceTraceIntersector*>(nullptr));
  }
  else if (source.CellDimension == 2)
  {
    f(static_cast<CurveTraceIntersector<TriangleIntersector>*>(nullptr));
  }
  else
  {
    f(static_cast<CurveTraceIntersector<TetrahedronIntersector>*>(nullptr));
  }
}
} // namespace mp

#endif
