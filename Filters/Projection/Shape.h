// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Shape.h
 * @brief What a leaf's meshes are, decided once both are wrapped: meshes of
 *        one dimension (2D in one plane, surfaces or curves in space, 3D),
 *        or a trace (a surface or curve inside a volume Source), and the
 *        frames both meshes are seen in.
 *
 * An empty mesh takes the other's dimension. Input of a higher dimension
 * than Source, a curve in a curved Source surface, a curve off a planar
 * Source's plane and 2D meshes in planes that are not parallel are errors.
 * A 2D leaf is a surface when either mesh leaves one plane, on any
 * process; a Source in a plane parallel to Input's is projected onto it,
 * with a warning. On several processes the processes' parts are gathered
 * so that every process decides as one process seeing the whole meshes
 * would.
 */
#ifndef MeshProjection_Projection_Shape_h
#define MeshProjection_Projection_Shape_h

#include "Parallel/Parts.h"

#include <string>

class vtkDataSet;

namespace mpvtk
{
class LeafAgreement;
struct LeafContext;
class Messages;
class SimplexMesh;
struct Settings;

struct LeafShape
{
  bool Trace = false;       ///< a surface or curve inside a volume Source
  bool Planar = false;      ///< seen in one plane (2D), or not a surface leaf at all
  std::string PlaneWarning; ///< Source in a parallel plane: said for the first leaf
  /// Input has second-order cells on some process (their own functions
  /// have no lumped mass and no node bounds): decided alike everywhere.
  bool SecondOrder = false;
  /// ... and every one of them has a Bernstein form (Kernel
  /// Transfer/BernsteinForm.h), in which point data is lumped and bounded:
  /// decided alike everywhere by ShareSystems (Apply.h).
  bool Bernstein = false;
  /// ... and some process's have a signed form (serendipity cells,
  /// pyramids: BernsteinForm.h), whose lumped point data is always
  /// bounded and whose uncovered rows every process sets alike
  /// (ApplyOptions::Signed): decided alike everywhere by DecideShape.
  bool Signed = false;
};

/**
 * Decides the leaf's shape (ctx.Shape) and puts both meshes in their frames
 * (takes part in the Shape round of `agreement`, its steps of this process
 * alone run through LeafAgreement::Local, the collective sums between them
 * not); a failure is the agreed verdict.
 */
Verdict DecideShape(LeafContext& ctx, LeafAgreement& agreement);

/**
 * Tells `mesh`, before it wraps `data` (this process's part of a mesh) at
 * level `asked`, the curved cells of the whole mesh that the finer split
 * does not take (SimplexMesh::SetWholeCurvedUnrefinable: summed over the
 * parts), so that every part splits as the whole mesh alone: one such cell
 * anywhere keeps every part on its nodes' split. A collective on several
 * processes when `asked` > 1; nothing on one process (Wrap counts).
 */
void ShareCurvedUnrefinable(Parts& parts, vtkDataSet* data, int asked, SimplexMesh& mesh);

/// Warns once per filter when `mesh` left out cells of lower dimension, or
/// kept curved cells on their nodes' split against CurvedCellSubdivision.
void WarnLeftOut(const SimplexMesh& mesh, const std::string& role, Messages& messages);
} // namespace mpvtk

#endif
