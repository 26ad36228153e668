// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file IntersectionOutput.h
 * @brief The kernel's intersection pieces as VTK datasets (the filter's
 *        optional intersection output).
 *
 * Each piece is the intersection of one source and one target simplex,
 * with its own points (pieces share none). Its cell data name the
 * datasets' cells, not the kernel's simplices: SourceCellId and
 * TargetCellId are the VTK ids of the original cells (through the meshes'
 * parents, so split cells and renumberings are undone), and the measure
 * (Length, Area or Volume) is the piece's own. 2D pieces computed in a
 * plane frame are put back into the target's plane in space.
 */
#ifndef MeshProjection_Adapter_IntersectionOutput_h
#define MeshProjection_Adapter_IntersectionOutput_h

#include "Adapter/SimplexMesh.h"
#include "Geometry/IntersectionPieces.h"

#include "vtkSmartPointer.h"

class vtkPolyData;
class vtkUnstructuredGrid;

namespace mpvtk
{
/// 2D: one polygon per intersecting pair in the target's plane, with
/// SourceCellId, TargetCellId (VTK ids) and Area.
vtkSmartPointer<vtkPolyData> MakeIntersectionPolygons(
  const mp::IntersectionPieces& pieces, const SimplexMesh& target, const SimplexMesh& source);
/// Curves: one segment per intersecting pair on the target's segment, with
/// SourceCellId, TargetCellId and Length.
vtkSmartPointer<vtkPolyData> MakeIntersectionSegments(
  const mp::IntersectionPieces& pieces, const SimplexMesh& target, const SimplexMesh& source);
/// 3D: the tetrahedra decomposing each intersection polyhedron, with
/// SourceCellId, TargetCellId and Volume.
vtkSmartPointer<vtkUnstructuredGrid> MakeIntersectionPolyhedra(
  const mp::IntersectionPieces& pieces, const SimplexMesh& target, const SimplexMesh& source);
} // namespace mpvtk

#endif
