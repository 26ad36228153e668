// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Measures.h
 * @brief The measure of every cell of a mesh, summed per parent cell.
 *
 * The area of each triangle (2D) or the volume of each tetrahedron (3D), as
 * the intersectors' Prepare computes it (so the same measure the covered
 * fractions are taken of; 0 for a degenerate cell), added up per original
 * cell (MeshView::ParentOf). Extensive cell data (totals) become densities
 * by these measures before a P0 projection; the covered fractions of split
 * cells are summed per original cell the same way.
 */
#ifndef MeshProjection_Kernel_Measures_h
#define MeshProjection_Kernel_Measures_h

#include "Geometry/Intersectors.h"
#include "Mesh/LargeArray.h"
#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"

#include <algorithm>
#include <type_traits>
#include <utility>
#include <vector>

namespace mp
{
/// Whether intersector I has PrepareMeasure (Prepare's measure alone).
template <class I, class = void>
struct HasPrepareMeasure : std::false_type
{};
template <class I>
struct HasPrepareMeasure<I,
  std::void_t<decltype(I::PrepareMeasure(
    std::declval<const MeshView&>(), Index(0), std::declval<double&>()))>> : std::true_type
{};

/// Calls visit(c, measure) for every cell of the mesh (of cells [begin,
/// end) when given) that is not degenerate.
template <class Visit>
void ForEachCellMeasure(const MeshView& mesh, Visit visit, Index begin = 0, Index end = -1)
{
  end = end < 0 ? mesh.NumberOfCells : end;
  WithIntersectorOf(mesh, [&](auto* tag) { // the intersector's type only
    using Intersector = std::remove_pointer_t<decltype(tag)>;
    if constexpr (HasPrepareMeasure<Intersector>::value)
    {
      double measure = 0.0;
      for (Index c = begin; c < end; ++c)
      {
        if (Intersector::PrepareMeasure(mesh, c, measure))
        {
          visit(c, measure);
        }
      }
    }
    else
    {
      typename Intersector::Cell cell;
      for (Index c = begin; c < end; ++c)
      {
        if (Intersector::Prepare(mesh, c, cell))
        {
          visit(c, cell.Measure);
        }
      }
    }
  });
}

inline std::vector<double> ParentMeasures(const MeshView& mesh)
{
  std::vector<double> measure(static_cast<size_t>(mesh.Parents()), 0.0);
  ForEachCellMeasure(
    mesh, [&](Index c, double m) { measure[static_cast<size_t>(mesh.ParentOf(c))] += m; });
  return measure;
}

/// Per original cell, the covered fraction of its measure, from the
/// covered fraction of each of its simplices.
inline LargeVector<double> ParentFractions(const MeshView& mesh,
  const LargeVector<double>& fraction, const TaskRunner& runner = TaskRunner())
{
  if (mesh.Parent && mesh.OneCellPerParent)
  {
    // Only renumbered: each parent's fraction is its one simplex's (already
    // at most 1; 0 for a simplex of no measure, which the search skips),
    // moved in `runner`'s tasks (each parent written once).
    LargeVector<double> moved(static_cast<size_t>(mesh.Parents()), 0.0);
    runner.ForRanges(
      mesh.NumberOfCells,
      [&](Index begin, Index end) {
        for (Index c = begin; c < end; ++c)
        {
          moved[static_cast<size_t>(mesh.Parent[c])] =
            std::min(1.0, fraction[static_cast<size_t>(c)]);
        }
        return 0;
      },
      Index(1) << 16);
    return moved;
  }
  std::vector<double> measure(static_cast<size_t>(mesh.Parents()), 0.0);
  LargeVector<double> covered(measure.size(), 0.0);
  ForEachCellMeasure(mesh, [&](Index c, double m) {
    const size_t p = static_cast<size_t>(mesh.ParentOf(c));
    measure[p] += m;
    covered[p] += fraction[static_cast<size_t>(c)] * m;
  });
  for (size_t p = 0; p < measure.size(); ++p)
  {
    covered[p] = measure[p] > 0.0 ? std::min(1.0, covered[p] / measure[p]) : 0.0;
  }
  return covered;
}
} // namespace mp

#endif
