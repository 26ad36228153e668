// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Composite.h
 * @brief Composite inputs as the projection sees them: Source's blocks
 *        appended into one dataset, Input's leaves with their output copies
 *        (the walk over leaves itself: Adapter/CompositeLeaves.h).
 */
#ifndef MeshProjection_Projection_Composite_h
#define MeshProjection_Projection_Composite_h

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkDataObject;
class vtkDataSet;

namespace mpvtk
{
struct JoinedFields;
class Messages;
class Parts;

/**
 * Source as one dataset: itself, or all the dataset leaves of a composite
 * Source appended (points not merged: cells of different blocks meeting at
 * an interface see each other through the locator, and a field continuous
 * across it gives the merged mesh's result). Each block is checked first
 * (CheckDataSet: an error names it); arrays with too few tuples are left
 * out and said in `note`. Fields that differ between the blocks (those
 * with cells) follow PieceArrays.h's rule, the same as between processes:
 * one some blocks lack is kept, NaN on those (a hole), one with other
 * types or components on some is left out; `joined` says which, with the
 * warnings. Null for a data object that is neither.
 */
vtkSmartPointer<vtkDataSet> AppendedSource(
  vtkDataObject* data, std::string& note, std::string& error, JoinedFields& joined);

/// One dataset of Input to project, and its copy in the output.
struct InputLeaf
{
  unsigned int FlatIndex = 0; ///< 0 for a dataset
  vtkDataSet* Target = nullptr;
  vtkDataSet* Output = nullptr;
  std::string Name;             ///< BlockName(), empty when Input is a dataset
  bool EmptyEverywhere = false; ///< no cells on any process
};

struct InputLeaves
{
  std::vector<InputLeaf> Leaves;
  /// Empty datasets standing for the blocks this process lacks.
  std::vector<vtkSmartPointer<vtkDataObject>> StandIns;
  std::vector<unsigned int> FlatIndices() const;
};

/**
 * The datasets of Input (itself, or its dataset leaves; other leaves are
 * skipped with a warning) with their copies in `output` (PassInput's). On
 * several processes every process gets every leaf that any has (the
 * solves are collective): an empty dataset stands for one it lacks, and a
 * leaf empty everywhere is marked so.
 */
InputLeaves LeavesOf(vtkDataObject* input, vtkDataObject* output, Parts& parts, Messages& say);
} // namespace mpvtk

#endif
