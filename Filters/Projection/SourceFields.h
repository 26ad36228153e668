// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SourceFields.h
 * @brief The Source arrays to project, gathered side by side as the kernel
 *        reads them, and the groups of arrays whose NaN or infinite values
 *        leave Source cells out.
 *
 * Per association (0: point arrays, P1 functions in the kernel's point
 * order; 1: cell arrays, P0 functions numbered as the dataset's cells),
 * the selected numeric fields (ArraySelection.h) are copied into one
 * functions x components block; extensive cell arrays become densities
 * (total / measure). An array with a NaN or infinite value leaves out the
 * Source cells that use it, for that array only: arrays that leave out the
 * same cells form a NaN group, projected by an operator of its own with
 * those cells as a hole, so that the rest of the covered part stays
 * conservative. On several processes every array with such values on any
 * process has a group of its own (the solves are collective). An array
 * that some of Source's pieces (processes) or blocks lack comes with NaN
 * there (Adapter/PieceArrays.h): those cells are its hole, the same way.
 */
#ifndef MeshProjection_Projection_SourceFields_h
#define MeshProjection_Projection_SourceFields_h

#include "Mesh/LargeArray.h"
#include "Mesh/MeshView.h"
#include "Projection/MassWeighting.h"

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

class vtkDataArray;
class vtkDataArraySelection;
class vtkDataSet;

namespace mpvtk
{
class Messages;
class Parts;
class SimplexMesh;
struct Settings;

/// The two associations of Source arrays (GatheredFields per association).
enum Association
{
  PointArrays = 0, ///< P1 functions (the kernel's points)
  CellArrays = 1   ///< P0 functions (the dataset's cells)
};

/// Arrays' values side by side, as the operators read them.
struct FieldBlock
{
  int Components = 0;
  mp::LargeVector<double> Values; ///< functions x Components
  /// With CellDataReconstruction: Values as DP1 functions (CellReconstruction.h).
  mp::LargeVector<double> Corners;
  bool Reconstructed = false;
  /// What the operators read: Corners when reconstructed, else Values.
  const mp::LargeVector<double>& Functions() const
  {
    return this->Reconstructed ? this->Corners : this->Values;
  }
};

/// Arrays with NaN or infinite values that leave out the same Source cells
/// (their Values: non-finite values as 0).
struct NaNGroup : FieldBlock
{
  std::vector<int> Arrays;    ///< indices into GatheredFields::Arrays
  std::vector<char> Excluded; ///< per kernel Source cell
  std::uint64_t Print = 0;    ///< of Excluded
};

/**
 * A Source array projected as labels (Labels.h): its distinct values and,
 * per source function of the operators that carry it, the index of its
 * label (-1: none, a NaN of a real array marked as labels).
 */
struct LabelField
{
  vtkDataArray* Array = nullptr;
  std::vector<double> Labels; ///< sorted; on several processes, every process's
  std::vector<int> Which;     ///< per source function (P1, P0 or DP1): index into Labels, or -1
  /// How many distinct labels: Labels.size(), or, for an id array found
  /// before the union (Labels.h: IndexLabels), the most one process had.
  size_t Distinct = 0;
  /// Whether Distinct is only a lower bound (an id array on several processes).
  bool AtLeast = false;
};

/// The Source arrays of one association, gathered side by side (NaN groups'
/// columns of Values as 0).
struct GatheredFields : FieldBlock
{
  /// The arrays projected as labels (Labels.h), not among Arrays.
  std::vector<LabelField> Labels;
  /// Whether any array of this association goes somewhere (numbers or labels).
  bool Any() const { return this->Components > 0 || !this->Labels.empty(); }
  std::vector<vtkDataArray*> Arrays;
  std::vector<int> Offsets;     ///< each array's first column
  std::string Key;              ///< names and components: which solution a warm start may reuse
  std::vector<NaNGroup> Groups; ///< the arrays with non-finite values
  /// Names of the arrays that some Source pieces or blocks lack, NaN there
  /// (Adapter/PieceArrays.h): their hole is said by that rule's warning.
  std::set<std::string> Holes;
  /// That rule's warnings (name, text), on arrays with a hole or refused:
  /// said when the array is selected.
  std::vector<std::pair<std::string, std::string>> PieceWarnings;
  /// Per array: 1 for the density gathered for mass weighting only (not
  /// selected): projected, not written.
  std::vector<char> Hidden;
  /// Which arrays are projected as rho q (MassWeighting.h).
  MassWeights Mass;
  /// Appends `array` (named `label`) to the arrays projected as numbers.
  void AddArray(vtkDataArray* array, const std::string& label, bool hidden);
  /// The labels of this process's own Source piece (before the gathering),
  /// per label array's name: on several processes the labels are the whole
  /// Source's, as one process sees them (Labels.h: IndexLabels).
  std::map<std::string, std::vector<double>> PieceLabels;
};

/// Per Source cell (parent, the dataset's cell): 1 where a NaN group leaves it out.
std::vector<char> LeftOutCells(const mp::MeshView& view, const NaNGroup& group);

/**
 * The fields of `source` (wrapped as `mesh`) that `selections` (points,
 * cells) enable, the labels (Labels.h: IsLabelArray) apart, extensive
 * cell arrays as densities (settings.Extensive), the density of a mass
 * weighting (MassWeighting.h; hidden when not enabled), weighted arrays as
 * rho q, tangent arrays' normal parts removed (settings.TangentArrays:
 * TangentFields.h); warns of arrays skipped (not numeric, too short) or
 * projected as real values (integers not handled as labels), of NaN
 * groups, and says the PieceWarnings of the arrays enabled (`fields` comes
 * with Holes and PieceWarnings set). Collective (the NaN groups, the
 * labels).
 */
void GatherSourceFields(vtkDataSet* source, const SimplexMesh& mesh,
  vtkDataArraySelection* const selections[2], const Settings& settings, Messages& messages,
  Parts& parts, GatheredFields fields[2]);
} // namespace mpvtk

#endif
