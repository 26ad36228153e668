// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Labels.h
 * @brief Categorical Source arrays (material ids, regions, classes): each
 *        target point or cell takes the label that covers most of it,
 *        weighed by the overlap matrix M_ts, never a mean of labels.
 *
 * Which arrays are labels (CategoricalMode): CategoricalAutomatic, every
 * single-component integer array (vtkIntArray, vtkShortArray,
 * vtkCharArray, vtkIdTypeArray, the unsigned ones...; not a vtkBitArray)
 * with at most MaximumAutomaticLabels distinct values over the whole
 * Source (more: an id array, projected as numbers with a warning:
 * CheckLabelCounts); CategoricalSelected,
 * exactly the single-component arrays named in CategoricalArrays (an
 * integer array then left out is projected as numbers; a real one named
 * is a label array).
 *
 * The rule, one for every transfer: with chi_L the indicator of the source
 * functions whose value is label L (P0: the cells; P1: the points; the
 * reconstruction's DP1: the cells' corners), the weight of label L at target
 * function i is w_iL = (M_ts chi_L)_i, the integral of the target basis
 * function phi_i over the part of the covered target where the source
 * functions of label L live (weighed by them): for cells, the measure of
 * the target cell covered by Source cells of label L. The target function
 * takes the label of largest weight; labels within 1e-12 (relative) of the
 * largest weight are a tie, which the smallest label wins. The fractions
 * w_iL / sum_L w_iL (the lumped projection of the indicators, which
 * MortarOperator::Apply gives) sum to 1, and over the cells, weighed by
 * their covered measure, sum to each label's Source measure over the
 * covered part. Functions the masks call invalid get FillLabel (and NaN
 * or FillValue fractions). Labels are not extrapolated.
 *
 * Memory does not grow with the number of labels: the indicators are
 * projected LabelBlock labels at a time (per row the sum of the weights,
 * their largest, then the winner: each block projected again), never all
 * side by side; the fractions, an output of one component per label, only
 * up to MaximumLabelFractions labels (their storage holds the weights
 * between the two passes: each block projected once).
 *
 * The operators that carry labels need M_ts (PlanOperators assembles it);
 * on several processes the labels are every process's (UnionOfValues) and
 * the shared rows' weights are summed by the solver's hooks, as the right-
 * hand sides of any lumped projection.
 */
#ifndef MeshProjection_Projection_Labels_h
#define MeshProjection_Projection_Labels_h

#include "Projection/Apply.h"
#include "Projection/Leaf.h"
#include "Projection/SourceFields.h"

#include "vtkSmartPointer.h"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

class vtkDataArray;
class vtkDataArraySelection;
class vtkDataSet;

namespace mpvtk
{
class Messages;
struct Settings;

/**
 * In CategoricalAutomatic, an integer array with more distinct values than
 * this over the whole Source is an id (cell or point numbers, Generate
 * Ids' "Ids"), not a label: material ids, regions and classes number at
 * most a few hundred, ids as many as the cells or points. A label array
 * with more is still projected (CategoricalSelected), in blocks.
 */
constexpr size_t MaximumAutomaticLabels = 1024;

/// The labels projected side by side at once (the indicators' and weights' columns).
constexpr int LabelBlock = 16;

/// A label array with more labels than this gets no fractions array (one component per label).
constexpr size_t MaximumLabelFractions = 256;

/// Whether `array` holds integers (any type but float and double): a label array by default.
bool HoldsIntegers(vtkDataArray* array);

/// Whether `array` (of `association`) is projected as labels by `settings`' rule (says why not,
/// to `messages` when given, when a named array cannot be one).
bool IsLabelArray(
  vtkDataArray* array, const Settings& settings, int association, Messages* messages);

/**
 * Before the Source is gathered: the labels of each array of this
 * process's piece `source` that `selections` (points, cells) enable and
 * `settings` makes a label array (GatheredFields::PieceLabels), so that
 * every process knows the whole Source's labels. (Arrays not projected
 * are not read.)
 */
void ListPieceLabels(vtkDataSet* source, vtkDataArraySelection* const selections[2],
  const Settings& settings, GatheredFields fields[2]);

/**
 * For each of g.Labels: its labels (every process's, and those of the
 * pieces the processes had before the gathering) and each source
 * function's label index, for the operators of that association (`dp1`:
 * cell data reconstructed, the cells' corners). Collective. With
 * `automatic` (CategoricalAutomatic), an array of which some process alone
 * has more than MaximumAutomaticLabels distinct values is an id array,
 * decided before the union (which would send each process's whole set to
 * every other): its Distinct is that count, and it has no labels or index.
 */
void IndexLabels(const SimplexMesh& mesh, int association, bool dp1, bool automatic, Parts& parts,
  GatheredFields& g);

/**
 * After IndexLabels, each of g.Labels with more than
 * MaximumAutomaticLabels labels (the same on every process): in
 * CategoricalAutomatic an id array, which goes to the arrays projected as
 * numbers, with a warning that names it; in CategoricalSelected still a
 * label array, with a warning of the time its blocks take.
 */
void CheckLabelCounts(
  int association, const Settings& settings, Messages& messages, GatheredFields& g);

/**
 * Per transfer in use and label array of its association: the winning
 * labels and, with LabelFractions, the fractions (solutions.Labels), from
 * the lumped projection of the labels' indicators by the transfer's
 * operator, LabelBlock labels at a time. Collective (every process has the
 * same labels, so the same blocks).
 */
Verdict ApplyLabels(LeafContext& ctx, const OperatorSet& ops, const mp::SolverHooks hooks[2],
  LeafSolutions& solutions);

/// Whether the label array `field` gets a fractions array (LabelFractions, few enough labels).
bool WritesFractions(const LabelField& field, const Settings& settings);

/**
 * One label array's output: `name`, the Source array's type, per target
 * point or cell (target function f at at(f)) the winning label where
 * `valid`, else the fill label (FillLabel; for an unsigned type that
 * cannot hold it, the type's largest value). When WritesFractions, also
 * the fractions array "<name>_Fractions" (one component per label, named
 * by it; invalid functions: the fill value).
 */
struct LabelOutput
{
  vtkSmartPointer<vtkDataArray> Labels;
  vtkSmartPointer<vtkDataArray> Fractions; ///< null unless asked for
};
LabelOutput WriteLabelArray(const LabelField& field, const LabelSolution& solution,
  const std::vector<char>& valid, vtkIdType n, const std::function<vtkIdType(vtkIdType)>& at,
  const std::string& name, const Settings& settings);
} // namespace mpvtk

#endif
