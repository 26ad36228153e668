// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SourceSide.h
 * @brief The source cells' own geometry when it is not the target's: traces.
 *
 * Every intersector meets cells of one kind on both sides (triangles with
 * triangles, tetrahedra with tetrahedra, ...), except the traces
 * (TraceIntersector.h), whose target is a surface or a curve and whose
 * source is a volume mesh. Such an intersector names the source's cells'
 * intersector as `SourceSide`: the search prepares, walks and counts faces
 * of source cells with it (PairSearch.h). `SourceSideOf<I>` is that, or I
 * itself.
 */
#ifndef MeshProjection_Kernel_SourceSide_h
#define MeshProjection_Kernel_SourceSide_h

#include "Mesh/MeshView.h"

#include <type_traits>

namespace mp
{
template <class I, class = void>
struct SourceSideOf
{
  using type = I;
};

template <class I>
struct SourceSideOf<I, std::void_t<typename I::SourceSide>>
{
  using type = typename I::SourceSide;
};

/// Whether I meets cells of another dimension on the source side (a trace).
template <class I>
constexpr bool IsTrace = !std::is_same<typename SourceSideOf<I>::type, I>::value;

/**
 * The cells of intersector Base (triangles in the plane, tetrahedra) with,
 * per face (Cell order), whether it lies on the mesh's boundary (no
 * neighbour; unknown, so never, for a mesh without neighbours).
 */
template <class Base>
struct BoundedCells : Base
{
  struct Cell : Base::Cell
  {
    unsigned Boundary = 0; ///< bit k: face k (Cell order) has no neighbour
  };
  static bool Prepare(const MeshView& mesh, Index id, Cell& cell)
  {
    if (!Base::Prepare(mesh, id, cell))
    {
      return false;
    }
    cell.Boundary = 0;
    for (int k = 0; mesh.Neighbors && k < Base::Faces; ++k)
    {
      cell.Boundary |= unsigned(mesh.Neighbor(id, cell.Face[k]) < 0) << k;
    }
    return true;
  }
};

/**
 * A source cell as the spaces see it on a trace's piece: its N barycentric
 * coordinates (the P1 functions of its points) as affine functions of the
 * target frame's D coordinates, Affine[j] = (value at the frame's origin,
 * gradient).
 */
template <int N, int D>
struct AffineCell
{
  Index Id = -1;
  Index Points[N];
  double Affine[N][D + 1];
};
} // namespace mp

#endif
