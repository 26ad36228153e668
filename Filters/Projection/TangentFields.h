// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TangentFields.h
 * @brief Vector fields tangent to a surface or curve (TangentArrays): their
 *        normal part removed on the Source before the projection and on
 *        Input after it, each mesh with its own geometry's normals.
 *
 * The projection treats the three Cartesian components as three scalar
 * fields; between two facetizations of a curved surface the result leaves
 * the target's tangent plane. A tangent array is projected that way, from
 * the Source's tangential part (the normal part removed at each Source
 * point or cell with the Source's normals), then its normal part at each
 * target point or cell (the target's normals) is removed and reported as
 * `<name>_NormalPart`. On a curve the tangent plane is the line: the part
 * along its tangent is kept.
 *
 * Normals are those of the dataset's own cells: a polygon's area vector
 * (Newell's formula: a triangle's is half the cross product of two edges),
 * a line's chord; at a point, the sum of the area vectors (or chords) of the
 * cells around it (the area-weighted mean direction), each taken with the
 * sign that agrees with the sum so far, so that a surface that flips its
 * cells' orientation still gets its normal. On several processes a target
 * point's sum is completed over the processes that share it (the solver's
 * hooks), each process's part first given the sign of the parts' common
 * axis (Mesh/AlignedSum.h), so that parts pointing opposite ways do not
 * cancel; the Source's points at the same coordinates share their sums
 * (its pieces' points on the cuts come once per piece: processes' parts
 * gathered without global ids, a composite's blocks), and the gathering
 * brings the cells around those that meet Input (Settings::GathersNeighborLayer). The normal part of a planar mesh is its plane's: removed to
 * round-off, linear tangent fields stay exact.
 */
#ifndef MeshProjection_Projection_TangentFields_h
#define MeshProjection_Projection_TangentFields_h

#include "Mesh/LargeArray.h"
#include "Transfer/BlockCG.h"

#include "vtkType.h"

#include <string>
#include <vector>

class vtkDataArray;
class vtkDataSet;

namespace mpvtk
{
class Messages;
class Parts;
class SimplexMesh;
struct GatheredFields;
struct Settings;

/// The largest normal part relative to the field's largest magnitude that passes without a warning.
constexpr double LargeNormalPart = 0.1;

/// Whether `array` is one of the arrays `settings` marks as tangent (by name, any number of components).
bool IsTangentArray(const Settings& settings, vtkDataArray* array);

/**
 * Per cell of `data` (3 values each): the area vector of a polygon when
 * `dimension` is 2, the chord of a line when 1; zero for cells of another
 * dimension and ghost cells left out (Adapter/Ghosts.h).
 */
std::vector<double> CellDirections(vtkDataSet* data, int dimension);

/**
 * Per point of `data` (3 values each): the sum of the directions of its
 * cells of `dimension` (CellDirections; a polyline's: those of its segments
 * around the point), each with the sign that agrees with the sum so far.
 */
std::vector<double> PointDirections(vtkDataSet* data, int dimension);

/**
 * Removes the normal part of the vector `v` (3 components) for the
 * direction `d` of a mesh of cells of `dimension` (2: `d` is the normal;
 * 1: the tangent, whose part is kept) and returns the magnitude removed. A
 * zero direction (a point without such cells) leaves `v` as it is.
 */
double RemoveNormalPart(double* v, const double* d, int dimension);

/**
 * The Source side: the normal part of each selected tangent array removed
 * at its points and cells (`fields` gathered from `source`, wrapped as
 * `mesh`), before the operators read them. Warns by name of a tangent
 * array that is not 3-component (projected as any other), of one on a
 * Source that is neither surface nor curve (volume: left as it is), and
 * of one whose removed part is large (LargeNormalPart: not a tangent
 * field on this Source).
 */
void RemoveSourceNormalParts(vtkDataSet* source, const SimplexMesh& mesh, const Settings& settings,
  Messages& messages, Parts& parts, GatheredFields fields[2]);

/**
 * The target side of one leaf: its point and cell directions (made on
 * first use), and the removal of the normal part of a projected array.
 */
class TargetTangents
{
public:
  /// `data` wrapped as `mesh`; `pointHooks` complete the points' sums across processes.
  TargetTangents(vtkDataSet* data, const SimplexMesh& mesh, const mp::SolverHooks& pointHooks,
    vtkIdType pointRows);
  /// Whether the target is a surface or curve (or a 2D mesh in a plane): tangents apply.
  bool Applies() const { return this->Dimension == 1 || this->Dimension == 2; }
  int CellDimension() const { return this->Dimension; }
  /**
   * Removes the normal part of `values` (functions x 3, the target's point
   * functions in the kernel's order when `points`, else its cells) where
   * `keep` says (valid or extrapolated); returns the magnitudes removed
   * per function (the others: `fill`) and the largest removed and largest
   * magnitude before (on this process).
   */
  std::vector<double> Remove(double* values, vtkIdType functions, bool points,
    const std::vector<char>& keep, double fill, double& largestRemoved, double& largestField);

private:
  const std::vector<double>& Directions(bool points);
  /// The points' sums completed over the processes that share them (AlignedSum.h). Collective.
  void CompleteSharedSums();
  vtkDataSet* Data;
  const SimplexMesh& Mesh;
  const mp::SolverHooks& Hooks;
  vtkIdType PointRows;
  int Dimension;
  std::vector<double> Cells;
  std::vector<double> Points; ///< in the kernel's point order
  bool HaveCells = false;
  bool HavePoints = false;
};
} // namespace mpvtk

#endif
