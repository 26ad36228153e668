// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FringeFrames.h
 * @brief The coordinates a fringe stencil is fitted in: the mesh's own on
 *        volume meshes, a point's tangent plane on surfaces and tangent
 *        line on curves.
 *
 * The fringe's extension (FringeAggregation.h) fits a polynomial through
 * free points around an ill-posed point i and evaluates it at i. On a
 * volume mesh (triangles in the plane, tetrahedra) the points span their
 * space and the fit is in their coordinates. The points of a surface in
 * 3D or of a curve do not span theirs: an affine fit in (x, y, z) is not
 * defined there. So on a surface the stencil's points are projected onto
 * the tangent plane at i (its normal the area-weighted mean of the normals
 * of i's triangles), on a curve onto the tangent line at i (the mean of its
 * segments' directions), and fitted there in 2D or 1D, as on a 2D mesh or
 * along a line:
 *
 * - on a plane surface (a straight curve) the projection is an affine map
 *   of the plane (line) onto the tangent coordinates: the fit reproduces
 *   the linear fields of the ambient space restricted to it;
 * - on a curved surface it reproduces the functions affine (or quadratic)
 *   in i's tangent coordinates, which a smooth field is to the fit's order
 *   over a stencil of a few cells;
 * - the normal coordinates of the stencil's points (their offsets from the
 *   tangent plane or line, of the order of h^2 / R on a surface or curve
 *   of radius R) let the fit also reproduce the ambient linear fields
 *   where the stencil is curved (FringeFits.h): a trace on a
 *   sphere in a volume keeps a linear Source field exact.
 *
 * A frame depends on the geometry of the cells around i only (their
 * corners sorted by their coordinates, the sums taken in that order): a
 * distributed target whose halo holds those cells gets the serial frame,
 * bit for bit, whatever its numbering.
 */
#ifndef MeshProjection_Kernel_FringeFrames_h
#define MeshProjection_Kernel_FringeFrames_h

#include "Mesh/MeshView.h"

namespace mp
{
/// The coordinates a stencil around one point is fitted in.
struct StencilFrame
{
  /// Tangent coordinates: SpaceDimension on volume meshes, 2 on surfaces, 1 on curves.
  int Dimension = 3;
  /// Normal coordinates: 0 on volume meshes, 3 - Dimension on surfaces and curves.
  int Normals = 0;
  /// The mesh's own coordinates (volume meshes): offsets taken as they are, no rounding.
  bool Ambient = true;
  /// An orthonormal basis when not Ambient: Dimension tangent axes, then Normals normal ones.
  double Axes[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };

  /// y[0 .. Dimension): the tangent coordinates of x - origin.
  void Offset(const MeshView& mesh, const double* x, const double* origin, double* y) const;
  /// z[0 .. Normals): the normal coordinates of x - origin (none on volume meshes).
  void NormalOffset(const MeshView& mesh, const double* x, const double* origin, double* z) const;
};

/**
 * The frame of point i of `mesh`, whose cells around it are
 * cells[0 .. count): Ambient on volume meshes; on surfaces and curves its
 * tangent plane or line. A point whose cells give no tangent (degenerate
 * cells, or none) gets the ambient frame: its points do not spread there,
 * so no stable fit is found and the fringe drops or frees it.
 */
StencilFrame StencilFrameOf(const MeshView& mesh, Index i, const Index* cells, Index count);
} // namespace mp

#endif
