// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MassWeighting.h
 * @brief Mass-weighted projection (DensityArray, MassWeightedArrays): an
 *        intensive array q projected so that the integral of rho q is
 *        conserved, as the ratio of the projections of rho q and rho.
 *
 * The Source's values of each weighted q are replaced by rho q before the
 * NaN groups are found and cell data reconstructed (WeighSourceFields), so
 * that rho q is projected by the operators, the fringe, the bounds and the
 * NaN rules of every other array, and rho is projected beside it (as a
 * hidden array when the user did not select it). After the solves, before
 * the extrapolation (DivideByDensity), q_t = (rho q)_t / rho_t where the
 * projected density is above DensityGuard times the Source's largest
 * |rho|; elsewhere q_t is the fill value and q is invalid there (its own
 * mask), and the extrapolation neither extends nor reads it there
 * (Extrapolation.cxx): the extended q stays within the range of the
 * divided values. With PreserveBounds, q_t is clipped to q's Source range. The
 * projected products are kept beside (LeafSolutions::Products): the
 * integrals SourceIntegral_<q> and TargetIntegral_<q> are those of rho q,
 * and ConserveSourceIntegral scales q by rho q's factor over rho's
 * (Outputs.cxx), so that the written rho_t q_t has the Source's integral.
 *
 * What is conserved: with cell targets (P0), the sum over covered cells of
 * |cell's covered part| rho_t q_t, i.e. the integral of the product of the
 * two output fields, equals the Source's integral of rho q over the
 * covered part. With point targets (P1), the projected product (rho q)_t
 * is the projection of the Source's (P1) rho q, with its integral as any
 * projected point array; that integral is the sum over points of
 * (integral of the point's basis function over the covered part) rho_t q_t,
 * the nodal quadrature of the two output fields' product. Why the ratio and
 * not a rho-weighted mass matrix: docs/design.md.
 */
#ifndef MeshProjection_Projection_MassWeighting_h
#define MeshProjection_Projection_MassWeighting_h

#include <string>
#include <vector>

class vtkDataSet;

namespace mp
{
struct SolverHooks;
}

namespace mpvtk
{
class Messages;
class Parts;
struct GatheredFields;
struct LeafContext;
struct LeafSolutions;
struct OperatorSet;
struct Settings;

/// A projected density at most this times the Source's largest |rho| does not divide (1e-10).
constexpr double DensityGuard = 1e-10;

/// The mass weighting of one association's gathered arrays.
struct MassWeights
{
  int Density = -1;          ///< index into GatheredFields::Arrays; -1: no weighting
  std::vector<int> Weighted; ///< the arrays projected as rho q, in order
  double Scale = 0;          ///< the Source's largest finite |rho| (over every process)
  /// Per weighted array and component (in Weighted's order): q's Source
  /// range, finite values, over every process (PreserveBounds' clip).
  std::vector<double> Low, High;
  bool Active() const { return this->Density >= 0 && !this->Weighted.empty(); }
  /// Weighted's index of array a, or -1.
  int WeightedIndex(int a) const;
};

/// The columns of the projected products (LeafSolutions::Products): all, and the w-th weighted array's first.
int ProductWidth(const GatheredFields& g);
int ProductOffset(const GatheredFields& g, int w);

/**
 * The association of the density (0 points, 1 cells) in `source`, -1
 * when there is none or no such array (said once by name, with the arrays
 * it leaves unweighted).
 */
int DensityAssociation(vtkDataSet* source, const Settings& settings, Messages& messages);

/**
 * Decides which of `g`'s arrays (association `association`, values
 * copied, NaN groups not yet found) are weighted, says the problems by
 * name, and multiplies their values by the density's. Collective on
 * several processes (the scale and the ranges are reduced).
 */
void WeighSourceFields(const Settings& settings, int association, int densityAssociation,
  vtkDataSet* source, Parts& parts, Messages& messages, GatheredFields& g);

/**
 * After the solves of one leaf, before its extrapolation: each weighted
 * array's values become the ratio of its projected product and the
 * projected density (the products put aside in `solutions`), guarded and,
 * with PreserveBounds, clipped; the guarded functions counted and said
 * once. Collective on several processes.
 */
void DivideByDensity(LeafContext& ctx, const OperatorSet& ops, const mp::SolverHooks hooks[2],
  LeafSolutions& solutions);
} // namespace mpvtk

#endif
