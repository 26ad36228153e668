// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PieceArrays.h
 * @brief The one rule for Source fields that differ between the pieces
 *        Source comes in: the processes' pieces (Parallel/SourceGather)
 *        and a composite Source's blocks (Projection/Composite).
 *
 * Only pieces with cells count (an empty piece has nothing to project and
 * makes no array "missing"). Per field (a name, per association):
 *  - on every piece, with one type and number of components: kept;
 *  - on some pieces only, alike on those: kept, with a hole where it is
 *    missing. The joined array holds NaN there, so that the NaN groups
 *    (Projection/SourceFields.h) leave those cells out of its projection,
 *    as for any NaN value; an integer field is joined as double (an
 *    integer holds no NaN). One warning names it and the pieces without it;
 *  - with different types or numbers of components on different pieces:
 *    refused, with a warning that names it and says how they differ.
 * Nothing is left out without a warning. The decision is made from what
 * every piece holds, so on several processes it is the same on all, with
 * the same texts.
 */
#ifndef MeshProjection_Adapter_PieceArrays_h
#define MeshProjection_Adapter_PieceArrays_h

#include <map>
#include <set>
#include <string>
#include <vector>

class vtkDataSet;

namespace mpvtk
{
/// A field of one piece: association (0 points, 1 cells), name, VTK type, components.
struct PieceField
{
  int Association = 0;
  std::string Name;
  int Type = 0;
  int Components = 0;
};

/// What the rule makes of the pieces' fields.
struct JoinedFields
{
  /// Per association, the fields kept, by name: the joined array's type and components.
  std::map<std::string, PieceField> Kept[2];
  /// Per association, the names of those kept with a hole (NaN where missing).
  std::set<std::string> Holes[2];
  /// Per association, the warning on each field with a hole or refused, by name.
  std::map<std::string, std::string> Warnings[2];
};

/// The fields (numeric, FieldArrays.h) of a dataset's points and cells.
std::vector<PieceField> FieldsOfPiece(vtkDataSet* data);

/**
 * The rule over `pieces` (each piece's fields; pieces without cells left
 * out by the caller), `names[i]` naming piece i in the warnings ("process
 * 1", "block 3"); `whole` names the pieces' kind ("pieces", "blocks").
 */
JoinedFields JoinPieceFields(const std::vector<std::vector<PieceField>>& pieces,
  const std::vector<std::string>& names, const std::string& whole);
} // namespace mpvtk

#endif
