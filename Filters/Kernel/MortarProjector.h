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
 * Build() does the search and sums the local integrals straight into M_tt
 * (compressed rows over the target's point graph) and, for the fields it is
 * given, into the right-hand sides M_ts u_s, so M_ts need not be stored.
 * Project() then solves with conjugate gradients (Jacobi preconditioner, to
 * rounding level; a sparse LDL^T when that does not converge).
 */
#ifndef MeshProjection_Kernel_MortarProjector_h
#define MeshProjection_Kernel_MortarProjector_h

#include "CandidateLocator.h"
#include "MeshView.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace mp
{
struct ProjectionOptions
{
  SearchMethod Method = SearchMethod::AdvancingFront;
  bool KeepPieces = false; ///< store the intersection pieces (see IntersectionPieces)
  /// Store M_ts so that Project(sourceValues, ...) can project any field
  /// later. Without it (faster, less memory) only the fields given to
  /// Build() are projected, their right-hand sides summed during the search.
  bool KeepMixedMatrix = true;
  /// Concurrent tasks for the search and the local integrals: the target
  /// cells are split into this many ranges (default 1: serial).
  int Tasks = 1;
  /// Conjugate-gradient iterations before the sparse direct solver takes
  /// over for the fields that have not converged (mass matrices of
  /// reasonable meshes need a few dozen).
  int MaxIterations = 500;
  /**
   * Runs task(0), ..., task(count - 1), concurrently if it can (the VTK
   * filter passes vtkSMPTools::For). Default: one after the other.
   */
  std::function<void(int count, const std::function<void(int)>& task)> RunTasks;
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
  double Search = 0;   ///< pair search + intersections + local integrals + their sums
  double Assembly = 0; ///< the sparsity pattern, coverage, M_ts when kept
  double Solve = 0;    ///< the last Project() (conjugate gradients, or the direct fallback)
};

class MortarProjector
{
public:
  MortarProjector();
  ~MortarProjector();
  MortarProjector(const MortarProjector&) = delete;
  MortarProjector& operator=(const MortarProjector&) = delete;

  /**
   * Computes the intersections and the mortar matrices. Both meshes must
   * have neighbours set for the advancing front (see CellNeighbors.h);
   * `locator` must index the source cells (unused by the brute force, may
   * then be null). `fields` (source points x `components`, row-major) are
   * the source fields to project with Project(targetValues, fill). Returns
   * false, with GetError() saying why, on unusable input.
   */
  bool Build(const MeshView& target, const MeshView& source, CandidateLocator* locator,
    const ProjectionOptions& options = ProjectionOptions(), const double* fields = nullptr,
    int components = 0);

  /**
   * Projects the fields given to Build() onto the target points (target
   * points x components, row-major). Invalid target points get `fill`.
   */
  bool Project(double* targetValues, double fill) const;

  /**
   * Projects any source field (source points x components, row-major); needs
   * ProjectionOptions::KeepMixedMatrix. Invalid target points get `fill`.
   */
  bool Project(const double* sourceValues, int components, double* targetValues,
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
   * Entries of M_ts (when kept) and of M_tt, for tests: the assembled value,
   * 0 if absent.
   */
  double MixedMassEntry(Index targetPoint, Index sourcePoint) const;
  double TargetMassEntry(Index targetPoint, Index otherTargetPoint) const;

  struct Internals; ///< implementation detail (matrices, solver)

private:
  template <class Intersector>
  bool Assemble(const MeshView& target, const MeshView& source, CandidateLocator* locator,
    const ProjectionOptions& options, const double* fields, int components);
  bool Solve(const double* rhs, int components, double* x, double fill) const;

  std::unique_ptr<Internals> Impl;
  bool KeepsMixedMatrix = true;
  std::vector<char> ValidPoints;
  Index NumberOfValidPoints = 0;
  std::vector<double> CoveredFraction;
  double CoveredMeasure = 0;
  Index OvercoveredCells = 0;
  SearchStatistics Statistics;
  mutable ProjectionTimings Timings;
  IntersectionPieces Pieces;
  std::string Error;
};
} // namespace mp

#endif
