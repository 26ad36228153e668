// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PlaneFrame.h
 * @brief A planar mesh in any plane of space, seen as a 2D mesh.
 *
 * The 2D geometry works in the coordinates (x, y) of each point. A mesh of
 * triangles lying in a plane of 3D space is brought there by a frame: an
 * origin and two orthonormal axes of its plane, plus the normal. The planes
 * x, y or z = constant get frames that only pick coordinates (exact: no
 * rounding, and for z = constant the points are used in place); any other
 * plane gets orthonormal axes (its points are mapped with rounding, the same
 * rounding for both meshes, so the exact predicates still see one
 * consistent geometry). This is the one place that knows about planes: the
 * VTK adapter fits the frame, maps the points, and maps the intersection
 * pieces and locator boxes back.
 */
#ifndef MeshProjection_Kernel_PlaneFrame_h
#define MeshProjection_Kernel_PlaneFrame_h

#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"

#include <vector>

namespace mp
{
class PlaneFrame
{
public:
  /**
   * Fits the plane of the corners of the cells of `mesh` (triangles).
   * Returns false when they do not lie in one plane: `deviation` is then
   * the largest distance of a corner from the fitted plane and `size` the
   * mesh's extent (the tolerance is 1e-9 of its size, or of the plane's
   * distance from the origin when larger). A mesh without cells gets the
   * plane z = 0. The corners' box and mean are read in `runner`'s tasks,
   * the mean summed in fixed blocks of corners, in block order: the same
   * plane for any number of tasks.
   */
  bool Fit(
    const MeshView& mesh, double& deviation, double& size, const TaskRunner& runner = TaskRunner());

  /// Signed distance of x from the plane.
  double Distance(const double* x) const;
  /// Whether `other`'s plane is parallel to this one (normals within 1e-9 rad).
  bool IsParallel(const PlaneFrame& other) const;
  /// The same test on two unit normals.
  static bool AreParallel(const double* n, const double* m);
  /// How far from the plane a point may lie and still count as in it (set by Fit).
  double Tolerance() const { return this->PlaneTolerance; }
  /// The plane is z = constant: the points' (x, y) are their 2D coordinates.
  bool IsIdentity() const { return this->Axes[0] == 0 && this->Axes[1] == 1; }
  /// x, y or z = constant: 2D coordinates are two of the point's own.
  bool IsAxisAligned() const { return this->Axes[0] >= 0; }
  /// The plane's offset: its signed distance from the origin along Normal.
  double Offset() const { return this->PlaneOffset; }
  const double* GetNormal() const { return this->Normal; }

  /// (u, v, 0): the 2D coordinates of x in the plane.
  void ToPlane(const double* x, double* uv) const;
  /// The point of the plane at 2D coordinates (u, v) (uv[2] ignored).
  void ToSpace(const double* uv, double* x) const;
  /// The points of `mesh` mapped into (u, v, 0), three per point.
  void ToPlane(const MeshView& mesh, std::vector<double>& uv) const;
  /// The same axes, for the parallel plane at signed distance `offset` from the origin.
  PlaneFrame Shifted(double offset) const;
  /// A 3D box holding the plane's part over the 2D box (xmin..ymax of box).
  void BoxToSpace(const double box[6], double spaceBox[6]) const;

private:
  void SetAxes();
  double Origin[3] = { 0, 0, 0 };
  double U[3] = { 1, 0, 0 };
  double V[3] = { 0, 1, 0 };
  double Normal[3] = { 0, 0, 1 };
  double PlaneOffset = 0;
  double PlaneTolerance = 0;
  int Axes[2] = { 0, 1 }; ///< coordinates picked, or -1 for a general plane
};
} // namespace mp

#endif
