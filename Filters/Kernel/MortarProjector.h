// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MortarProjector.h
 * @brief Mortar L2 projection of P1 fields from a source mesh onto a target mesh.
 *
 * Given the target mesh T (P1 basis phi_i) and the source mesh S (P1 basis
 * psi_j), the projection u_t of a source field u_s solves
 *
 *     M_tt u_t = M_ts u_s,  (M_tt)_ik = int phi_i phi_k,  (M_ts)_ij = int phi_i psi_j,
 *
 * both integrals taken over T intersected with S, i.e. summed over the
 * intersection polygons of all (target, source) cell pairs found by the pair
 * search. Integrating M_tt over the covered part (rather than over all of T)
 * keeps the two properties users rely on even when the meshes do not cover
 * the same domain: a source field that is linear is reproduced exactly, and
 * the integral of u_t over the covered part equals that of u_s.
 *
 * Target points whose support meets no source cell cannot be determined:
 * they are reported invalid and receive a fill value.
 *
 * Build() does the search, assembly and a sparse LDL^T factorization (Eigen)
 * once; Project() then costs one sparse product and two triangular solves
 * per field component.
 */
#ifndef MeshProjection_Kernel_MortarProjector_h
#define MeshProjection_Kernel_MortarProjector_h

#include "CandidateLocator.h"
#include "MeshView.h"

#include <memory>
#include <string>
#include <vector>

namespace mp
{
struct ProjectionOptions
{
  SearchMethod Method = SearchMethod::AdvancingFront;
  bool KeepPieces = false; ///< store the intersection polygons (see Pieces)
};

/**
 * The intersection pieces of positive measure, for display and checks: in 2D
 * one convex polygon per intersecting cell pair, in 3D the tetrahedra that
 * decompose each intersection polyhedron (several per pair).
 */
struct IntersectionPieces
{
  int Dimension = 2;
  std::vector<Index> Offsets{ 0 }; ///< cell c has vertices [Offsets[c], Offsets[c+1])
  std::vector<double> Points;      ///< x, y, z per vertex (z = 0 for 2D)
  std::vector<Index> TargetCell;
  std::vector<Index> SourceCell;
  std::vector<double> Measure;     ///< area (2D) or volume (3D) of each cell
  Index Size() const { return static_cast<Index>(this->TargetCell.size()); }
};

/// Wall-clock seconds of the stages of Build().
struct ProjectionTimings
{
  double Search = 0;   ///< pair search + intersections + local mortar integrals
  double Assembly = 0; ///< sparse matrices from the local contributions
  double Factorization = 0;
};

class MortarProjector
{
public:
  MortarProjector();
  ~MortarProjector();
  MortarProjector(const MortarProjector&) = delete;
  MortarProjector& operator=(const MortarProjector&) = delete;

  /**
   * Computes intersections and mortar matrices and factorizes M_tt. Both
   * meshes must have neighbours set for the advancing front (see
   * CellNeighbors.h); `locator` must index the source cells (it is unused by
   * the brute-force search and may then be null). Returns false, with
   * GetError() saying why, on unusable input.
   */
  bool Build(const MeshView& target, const MeshView& source, CandidateLocator* locator,
    const ProjectionOptions& options = ProjectionOptions());

  /**
   * Projects a source point field (NumberOfPoints x components, row-major)
   * to the target points (same layout). Invalid target points get `fill`.
   */
  void Project(const double* sourceValues, int components, double* targetValues,
    double fill) const;

  /// Per target point: 1 if its support meets the source, else 0.
  const std::vector<char>& GetValidPoints() const { return this->ValidPoints; }
  Index GetNumberOfValidPoints() const { return this->NumberOfValidPoints; }
  /// Per target cell: the covered fraction of its measure (0 for degenerate cells).
  const std::vector<double>& GetCoveredFraction() const { return this->CoveredFraction; }
  /// Target cells whose pieces add up to more than the cell (the source overlaps itself).
  Index GetNumberOfOvercoveredCells() const { return this->OvercoveredCells; }
  /// Area (2D) or volume (3D) of the union of all pieces: the covered part of the target.
  double GetCoveredMeasure() const { return this->CoveredMeasure; }
  const SearchStatistics& GetStatistics() const { return this->Statistics; }
  const ProjectionTimings& GetTimings() const { return this->Timings; }
  const IntersectionPieces& GetPieces() const { return this->Pieces; }
  const std::string& GetError() const { return this->Error; }

  /**
   * Row i of M_ts as (source point, value) pairs and the entries of M_tt,
   * for tests: returns the value of the assembled entry (0 if absent).
   */
  double MixedMassEntry(Index targetPoint, Index sourcePoint) const;
  double TargetMassEntry(Index targetPoint, Index otherTargetPoint) const;

private:
  template <class Intersector>
  bool Assemble(const MeshView& target, const MeshView& source, CandidateLocator* locator,
    const ProjectionOptions& options);

  struct Internals;
  std::unique_ptr<Internals> Impl;
  std::vector<char> ValidPoints;
  Index NumberOfValidPoints = 0;
  std::vector<double> CoveredFraction;
  double CoveredMeasure = 0;
  Index OvercoveredCells = 0;
  SearchStatistics Statistics;
  ProjectionTimings Timings;
  IntersectionPieces Pieces;
  std::string Error;
};
} // namespace mp

#endif
