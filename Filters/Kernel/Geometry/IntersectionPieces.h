// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file IntersectionPieces.h
 * @brief The intersection pieces of positive measure, as plain arrays.
 *
 * For display and checks: in 2D one convex polygon per intersecting cell
 * pair, in 3D the tetrahedra that decompose each intersection polyhedron
 * (several per pair). The intersectors append their pieces here
 * (AppendPiece); it is geometry only, so it lives beside them.
 */
#ifndef MeshProjection_Kernel_IntersectionPieces_h
#define MeshProjection_Kernel_IntersectionPieces_h

#include "Mesh/MeshView.h"

#include <cstddef>
#include <vector>

namespace mp
{
struct IntersectionPieces
{
  int Dimension = 2;               ///< of the pieces: 2 polygons, 3 tetrahedra
  std::vector<Index> Offsets{ 0 }; ///< cell c has vertices [Offsets[c], Offsets[c+1])
  std::vector<double> Points;      ///< x, y, z per vertex (z = 0 for 2D)
  std::vector<Index> TargetCell;
  std::vector<Index> SourceCell;
  std::vector<double> Measure; ///< area (2D) or volume (3D) of each cell
  Index Size() const { return static_cast<Index>(this->TargetCell.size()); }
  std::size_t MemoryBytes() const
  {
    return (this->Offsets.capacity() + this->TargetCell.capacity() + this->SourceCell.capacity()) *
      sizeof(Index) +
      (this->Points.capacity() + this->Measure.capacity()) * sizeof(double);
  }

  /// Appends `other`'s cells after this one's.
  void Append(const IntersectionPieces& other)
  {
    const Index shift = this->Offsets.back();
    for (std::size_t i = 1; i < other.Offsets.size(); ++i)
    {
      this->Offsets.push_back(other.Offsets[i] + shift);
    }
    this->Points.insert(this->Points.end(), other.Points.begin(), other.Points.end());
    this->TargetCell.insert(
      this->TargetCell.end(), other.TargetCell.begin(), other.TargetCell.end());
    this->SourceCell.insert(
      this->SourceCell.end(), other.SourceCell.begin(), other.SourceCell.end());
    this->Measure.insert(this->Measure.end(), other.Measure.begin(), other.Measure.end());
  }
};
} // namespace mp

#endif
